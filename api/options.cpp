#include "api/options.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>

namespace papernet {
namespace {

using nlohmann::json;

// An options document is a flat object of a dozen scalars. Bigger or deeper ones are refused
// before the DOM grows: nesting is otherwise unbounded, and printing a deeply nested value in a
// message recursed until the stack ran out (docs/reliability.md).
constexpr std::size_t kMaxShownValue = 80;

/// The deepest nesting of arrays and objects in JSON text (brackets in strings do not count).
/// A scan rather than nlohmann's parse callback, whose DOM builder is quadratic in siblings.
int json_depth(std::string_view text) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::toupper(c); });
  return s;
}

[[noreturn]] void bad_value(const std::string& name, const json& value, const std::string& want) {
  std::string shown = value.is_string() ? value.get<std::string>() : value.dump();
  if (shown.size() > kMaxShownValue) shown = shown.substr(0, kMaxShownValue) + "...";
  throw OptionsError("invalid_option_value", name,
                     "option '" + name + "': '" + shown + "' is not " + want);
}

// Values come typed from JSON or as text from a query string; both are accepted everywhere.
double number(const std::string& name, const json& value) {
  if (value.is_number()) return value.get<double>();
  if (value.is_string()) {
    const std::string& s = value.get_ref<const std::string&>();
    double out = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    if (ec == std::errc() && end == s.data() + s.size() && !s.empty()) return out;
  }
  bad_value(name, value, "a number");
}

std::uint64_t whole(const std::string& name, const json& value) {
  if (value.is_number_unsigned()) return value.get<std::uint64_t>();
  if (value.is_string()) {
    const std::string& s = value.get_ref<const std::string&>();
    std::uint64_t out = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    if (ec == std::errc() && end == s.data() + s.size() && !s.empty()) return out;
  }
  bad_value(name, value, "a non-negative whole number");
}

bool boolean(const std::string& name, const json& value) {
  if (value.is_boolean()) return value.get<bool>();
  if (value.is_string()) {
    const std::string s = value.get<std::string>();
    if (s == "true" || s == "1" || s == "yes") return true;
    if (s == "false" || s == "0" || s == "no") return false;
  }
  bad_value(name, value, "true or false");
}

// true/false (the option was a boolean first) or a mode name.
TabMode tab_mode(const std::string& name, const json& value) {
  if (value.is_boolean()) return value.get<bool>() ? TabMode::Auto : TabMode::None;
  if (value.is_string()) {
    std::string s = value.get<std::string>();
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (s == "auto" || s == "true" || s == "1" || s == "yes") return TabMode::Auto;
    if (s == "strips") return TabMode::Strips;
    if (s == "none" || s == "false" || s == "0" || s == "no") return TabMode::None;
  }
  bad_value(name, value, "one of auto, strips, none (or true, false)");
}

std::string text(const std::string& name, const json& value) {
  if (value.is_string()) return value.get<std::string>();
  bad_value(name, value, "a string");
}

void apply(JobOptions& o, const std::string& name, const json& v) {
  if (name == "strategy") {
    const std::string s = upper(text(name, v));
    if (s == "QQ")
      o.strategy = Strategy::QQ;
    else if (s == "SEMP")
      o.strategy = Strategy::SEMP;
    else if (s == "SEQ")
      o.strategy = Strategy::SEQ;
    else if (s == "TU")
      o.strategy = Strategy::TU;
    else
      bad_value(name, v, "one of QQ, SEMP, SEQ, TU");
  } else if (name == "seed") {
    o.seed = whole(name, v);
  } else if (name == "target_faces") {
    o.target_faces = whole(name, v);
  } else if (name == "simplify") {
    o.simplify = whole(name, v);
  } else if (name == "time_limit") {
    o.time_limit = number(name, v);
  } else if (name == "size_mm") {
    o.size_mm = number(name, v);
  } else if (name == "scale") {
    o.scale = number(name, v);
  } else if (name == "paper") {
    const std::string s = upper(text(name, v));
    if (s == "A4")
      o.paper = PaperSize::A4;
    else if (s == "LETTER")
      o.paper = PaperSize::Letter;
    else if (s == "A3")
      o.paper = PaperSize::A3;
    else if (s == "NONE")
      o.paper = PaperSize::None;
    else
      bad_value(name, v, "one of A4, Letter, A3, none");
  } else if (name == "margin_mm") {
    o.margin_mm = number(name, v);
  } else if (name == "tabs") {
    o.tabs = tab_mode(name, v);
  } else if (name == "tab_room_budget") {
    o.tab_room_budget = whole(name, v);
  } else if (name == "flat_fold_degrees") {
    o.flat_fold_degrees = number(name, v);
  } else if (name == "keep_largest_component") {
    o.keep_largest_component = boolean(name, v);
  } else {
    throw OptionsError("unknown_option", name,
                       "unknown option '" + name +
                           "' (known: strategy, seed, target_faces, simplify, time_limit, "
                           "size_mm, scale, paper, margin_mm, tabs, tab_room_budget, "
                           "flat_fold_degrees, keep_largest_component)");
  }
}

void range(bool ok, const std::string& name, const std::string& message) {
  if (!ok) throw OptionsError("option_out_of_range", name, "option '" + name + "' " + message);
}

}  // namespace

std::string strategy_name(Strategy strategy) {
  switch (strategy) {
    case Strategy::QQ:
      return "QQ";
    case Strategy::SEMP:
      return "SEMP";
    case Strategy::SEQ:
      return "SEQ";
    case Strategy::TU:
      return "TU";
  }
  return "QQ";
}

std::string paper_name(PaperSize paper) {
  switch (paper) {
    case PaperSize::A4:
      return "A4";
    case PaperSize::Letter:
      return "Letter";
    case PaperSize::A3:
      return "A3";
    case PaperSize::None:
      return "none";
  }
  return "A4";
}

void validate_options(const JobOptions& o, const OptionsLimits& limits) {
  if (o.target_faces)
    range(*o.target_faces >= 4 && *o.target_faces <= limits.max_target_faces, "target_faces",
          "must be between 4 and " + std::to_string(limits.max_target_faces));
  if (o.simplify)
    range(*o.simplify >= 4 && *o.simplify <= limits.max_target_faces, "simplify",
          "must be between 4 and " + std::to_string(limits.max_target_faces));
  if (o.time_limit)
    range(
        std::isfinite(*o.time_limit) && *o.time_limit > 0 && *o.time_limit <= limits.max_time_limit,
        "time_limit",
        "must be more than 0 and at most " + std::to_string(limits.max_time_limit) + " seconds");
  if (o.size_mm)
    range(std::isfinite(*o.size_mm) && *o.size_mm > 0 && *o.size_mm <= 100'000, "size_mm",
          "must be more than 0 and at most 100000 millimetres");
  if (o.scale)
    range(std::isfinite(*o.scale) && *o.scale > 0 && *o.scale <= 1e6, "scale",
          "must be more than 0 and at most 1e6 millimetres per unit");
  if (o.size_mm && o.scale)
    throw OptionsError("conflicting_options", "scale",
                       "options 'size_mm' and 'scale' both set the print size; give one");
  range(std::isfinite(o.margin_mm) && o.margin_mm >= 0 && o.margin_mm <= 50, "margin_mm",
        "must be between 0 and 50 millimetres");
  range(o.tab_room_budget <= kMaxTabRoomBudget, "tab_room_budget",
        "must be at most " + std::to_string(kMaxTabRoomBudget) + " moves");
  range(std::isfinite(o.flat_fold_degrees) && o.flat_fold_degrees >= 0 && o.flat_fold_degrees < 90,
        "flat_fold_degrees", "must be at least 0 and less than 90 degrees");
}

JobOptions parse_options_query(const std::multimap<std::string, std::string>& params,
                               const OptionsLimits& limits) {
  JobOptions options;
  for (auto it = params.begin(); it != params.end(); ++it) {
    if (params.count(it->first) > 1)
      throw OptionsError("invalid_option_value", it->first,
                         "option '" + it->first + "' is given more than once");
    apply(options, it->first, json(it->second));
  }
  validate_options(options, limits);
  return options;
}

JobOptions parse_options_json(std::string_view text, const OptionsLimits& limits) {
  if (text.size() > kMaxOptionsJsonBytes)
    throw OptionsError("malformed_options", "",
                       "the options part has " + std::to_string(text.size()) + " bytes; at most " +
                           std::to_string(kMaxOptionsJsonBytes) + " are accepted");
  if (json_depth(text) > kMaxOptionsJsonDepth)
    throw OptionsError(
        "malformed_options", "",
        "the options part nests deeper than " + std::to_string(kMaxOptionsJsonDepth) + " levels");
  const json doc = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (doc.is_discarded())
    throw OptionsError("malformed_options", "", "the options part is not valid JSON");
  if (!doc.is_object())
    throw OptionsError("malformed_options", "", "the options part must be a JSON object");
  JobOptions options;
  for (const auto& [name, value] : doc.items()) {
    if (value.is_null()) continue;  // null means "the default", as if absent
    apply(options, name, value);
  }
  validate_options(options, limits);
  return options;
}

nlohmann::json options_to_json(const JobOptions& o) {
  auto opt = [](const auto& v) { return v ? json(*v) : json(nullptr); };
  return json{{"strategy", strategy_name(o.strategy)},
              {"seed", o.seed},
              {"target_faces", opt(o.target_faces)},
              {"simplify", opt(o.simplify)},
              {"time_limit", opt(o.time_limit)},
              {"size_mm", opt(o.size_mm)},
              {"scale", opt(o.scale)},
              {"paper", paper_name(o.paper)},
              {"margin_mm", o.margin_mm},
              {"tabs", tab_mode_name(o.tabs)},
              {"tab_room_budget", o.tab_room_budget},
              {"flat_fold_degrees", o.flat_fold_degrees},
              {"keep_largest_component", o.keep_largest_component}};
}

}  // namespace papernet
