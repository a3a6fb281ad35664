#include "api/options.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string_view>

#include "api/callback_url.h"
#include "core/ascii.h"
#include "core/io/json_text.h"

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
  std::string shown = value.is_string() ? value.get<std::string>() : json_text(value);
  if (shown.size() > kMaxShownValue) shown = shown.substr(0, kMaxShownValue) + "...";
  throw InvalidOptionException("invalid_option_value", name,
                               "option '" + name + "': '" + shown + "' is not " + want);
}

// Values come typed from JSON or as text from a query string or a command line; both are
// accepted everywhere.
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

std::optional<bool> boolean_word(std::string s) {
  s = ascii_lower(std::move(s));
  if (s == "true" || s == "1" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "0" || s == "no" || s == "off") return false;
  return std::nullopt;
}

bool boolean(const std::string& name, const json& value) {
  if (value.is_boolean()) return value.get<bool>();
  if (value.is_string())
    if (const std::optional<bool> b = boolean_word(value.get<std::string>())) return *b;
  bad_value(name, value, "true or false");
}

std::string text(const std::string& name, const json& value) {
  if (value.is_string()) return value.get<std::string>();
  bad_value(name, value, "a string");
}

Strategy strategy(const std::string& name, const json& value) {
  const std::string s = upper(text(name, value));
  if (s == "QQ" || s == "Q/Q") return Strategy::QQ;
  if (s == "SEMP" || s == "SE/MP") return Strategy::SEMP;
  if (s == "SEQ" || s == "SE/Q") return Strategy::SEQ;
  if (s == "TU") return Strategy::TU;
  if (s == "AUTO") return Strategy::AUTO;
  bad_value(name, value, "one of AUTO, QQ, SEMP, SEQ, TU");
}

// true/false (the option was a boolean first) or a mode name.
TabMode tab_mode(const std::string& name, const json& value) {
  if (value.is_boolean()) return value.get<bool>() ? TabMode::Auto : TabMode::None;
  if (value.is_string()) {
    const std::string s = ascii_lower(value.get<std::string>());
    if (s == "auto") return TabMode::Auto;
    if (s == "strips") return TabMode::Strips;
    if (s == "none") return TabMode::None;
    if (const std::optional<bool> b = boolean_word(s)) return *b ? TabMode::Auto : TabMode::None;
  }
  bad_value(name, value, "one of auto, strips, none (or true, false)");
}

FitGoal fit_goal(const std::string& name, const json& value) {
  const std::string s = ascii_lower(text(name, value));
  if (s == "sheets") return FitGoal::Sheets;
  if (s == "pieces") return FitGoal::Pieces;
  bad_value(name, value, "sheets or pieces");
}

Detail detail(const std::string& name, const json& value) {
  if (value.is_string()) {
    const std::string s = ascii_lower(value.get<std::string>());
    if (s == "auto") return {DetailMode::Auto, 0};
    if (s == "full") return {DetailMode::Full, 0};
  }
  if (value.is_number_unsigned() || value.is_string()) {
    try {
      return {DetailMode::Faces, whole(name, value)};
    } catch (const InvalidOptionException&) {
    }
  }
  bad_value(name, value, "auto, full or a face count");
}

std::string paper(const std::string& name, const json& value) {
  const std::string s = text(name, value);
  if (ascii_lower(s) == "none") return "none";
  try {
    return parse_paper(s).name;
  } catch (const InvalidOptionException&) {
    bad_value(name, value, "a paper: " + paper_names() + " (e.g. 300x200mm) or none");
  }
}

// The kit's name: UTF-8 (nlohmann's dump refuses anything else), no control character (C0,
// DEL or C1), at most kMaxTitleChars characters once the spaces at its ends are dropped.
std::string title(const std::string& name, const json& value) {
  std::string s = text(name, value);
  const auto first = s.find_first_not_of(' '), last = s.find_last_not_of(' ');
  s = first == std::string::npos ? std::string() : s.substr(first, last - first + 1);
  try {
    (void)json(s).dump();
  } catch (const json::type_error&) {
    bad_value(name, value, "UTF-8 text");
  }
  std::size_t chars = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto byte = static_cast<unsigned char>(s[i]);
    const bool c1 = byte == 0xC2 && i + 1 < s.size() &&
                    static_cast<unsigned char>(s[i + 1]) >= 0x80 &&
                    static_cast<unsigned char>(s[i + 1]) <= 0x9F;
    if (byte < 0x20 || byte == 0x7F || c1)
      bad_value(name, value, "text without control characters");
    chars += (byte & 0xC0) != 0x80;
  }
  if (chars > kMaxTitleChars)
    throw InvalidOptionException("option_out_of_range", name,
                                 "option '" + name + "': at most " +
                                     std::to_string(kMaxTitleChars) + " characters (" +
                                     std::to_string(chars) + " given)");
  return s;
}

// Every option: its name, how the command line shows its value, what it does, and how it is
// read. Lengths (`_mm`) take units on the command line.
struct Spec {
  const char* name;
  const char* value;  // "" for yes/no options
  const char* help;
  void (*apply)(JobOptions&, const std::string& name, const json& value);
};

constexpr Spec kOptions[] = {
    {"strategy", "AUTO|QQ|SEMP|SEQ|TU",
     "QQ, SEMP, SEQ: progressive unfolding after collapsing the mesh; TU: Tabu Unfolding of the "
     "full mesh; AUTO: QQ, and when it stops short of the full mesh, Tabu Unfolding from there "
     "(an approximation only when neither finds a net)",
     [](JobOptions& o, const std::string& n, const json& v) { o.strategy = strategy(n, v); }},
    {"seed", "N", "seed of every random choice: the same seed, the same net",
     [](JobOptions& o, const std::string& n, const json& v) { o.seed = whole(n, v); }},
    {"target_faces", "N",
     "faces of the coarse mesh progressive unfolding starts from (unset: F/10 + "
     "sqrt(F)(1+genus))",
     [](JobOptions& o, const std::string& n, const json& v) { o.target_faces = whole(n, v); }},
    {"detail", "auto|full|N",
     "faces printed: auto collapses a model denser than a person can build at its size (edges "
     "under about 18 mm) to fewer, larger faces; full keeps every face; N collapses to N faces. "
     "A collapsed net is approximate (the result says how far from the model)",
     [](JobOptions& o, const std::string& n, const json& v) { o.detail = detail(n, v); }},
    {"simplify", "N", "older name of detail N",
     [](JobOptions& o, const std::string& n, const json& v) {
       o.detail = {DetailMode::Faces, whole(n, v)};
     }},
    {"time_limit", "S",
     "seconds the whole job may take (unset: 60 on the command line, the server's setting there)",
     [](JobOptions& o, const std::string& n, const json& v) { o.time_limit = number(n, v); }},
    {"size_mm", "LEN",
     "longest side of the folded model (unset: 200 mm); a print holds a surface of at most 20 m², "
     "on at most 1,000 sheets",
     [](JobOptions& o, const std::string& n, const json& v) { o.size_mm = number(n, v); }},
    {"scale", "F", "millimetres per model unit (instead of the size)",
     [](JobOptions& o, const std::string& n, const json& v) { o.scale = number(n, v); }},
    {"paper", "P",
     "A4, A3, A5, Letter, Legal, Tabloid (11 x 17 in), WxHmm, or none (the SVG sized to the net)",
     [](JobOptions& o, const std::string& n, const json& v) { o.paper = paper(n, v); }},
    {"margin_mm", "LEN", "page margin, mm",
     [](JobOptions& o, const std::string& n, const json& v) { o.margin_mm = number(n, v); }},
    {"overlap_mm", "LEN", "overlap of the tiles of a net larger than a page, mm",
     [](JobOptions& o, const std::string& n, const json& v) { o.overlap_mm = number(n, v); }},
    {"layout", "fit|tile",
     "fit: pieces larger than a page are cut along folds (smaller still, or grown anew from "
     "single faces, where that saves sheets) and every piece is nested whole onto the fewest "
     "sheets (a face larger than a "
     "sheet is an error); tile: each part one piece, "
     "tiled across pages to tape together (unset: fit, or tile when a face is larger than a "
     "sheet)",
     [](JobOptions& o, const std::string& n, const json& v) {
       const std::string s = ascii_lower(text(n, v));
       if (s == "fit")
         o.layout = PageLayoutMode::Fit;
       else if (s == "tile")
         o.layout = PageLayoutMode::Tile;
       else
         bad_value(n, v, "fit or tile");
     }},
    {"prefer", "sheets|pieces",
     "layout fit: sheets, the fewest sheets, one fewer worth up to 20 more pieces and glue strips "
     "to cut out; pieces, the fewest pieces and strips, one fewer worth up to 20 more sheets",
     [](JobOptions& o, const std::string& n, const json& v) { o.prefer = fit_goal(n, v); }},
    {"tabs", "MODE",
     "auto: a glue tab where one fits, else a separate glue strip; strips: strips only; none: "
     "no glue",
     [](JobOptions& o, const std::string& n, const json& v) { o.tabs = tab_mode(n, v); }},
    {"tab_height_mm", "LEN", "tallest glue tab, widest strip half, mm (0: no glue)",
     [](JobOptions& o, const std::string& n, const json& v) { o.tab_height_mm = number(n, v); }},
    {"min_tab_height_mm", "LEN", "lowest tab printed, or half a shorter edge, mm",
     [](JobOptions& o, const std::string& n, const json& v) {
       o.min_tab_height_mm = number(n, v);
     }},
    {"tab_room_budget", "N",
     "candidate moves of the pass that changes the cuts so more edges have room for a tab, in "
     "each of its two rounds (0: no pass)",
     [](JobOptions& o, const std::string& n, const json& v) { o.tab_room_budget = whole(n, v); }},
    {"merge_budget", "N",
     "moved-face tests the merge of pieces after the fit search may spend (layout fit; 0: no "
     "merge): more merges more pieces on some meshes, at seconds more",
     [](JobOptions& o, const std::string& n, const json& v) { o.merge_budget = whole(n, v); }},
    {"flat_fold_degrees", "DEG", "folds flatter than this are not drawn",
     [](JobOptions& o, const std::string& n, const json& v) {
       o.flat_fold_degrees = number(n, v);
     }},
    {"labels", "", "matching numbers on both sides of each cut edge",
     [](JobOptions& o, const std::string& n, const json& v) { o.labels = boolean(n, v); }},
    {"colour", "auto|none",
     "auto: the model's textures, material and vertex colours printed on the pieces and their "
     "tabs; none: line art only",
     [](JobOptions& o, const std::string& n, const json& v) {
       const std::string s =
           v.is_boolean() ? (v.get<bool>() ? "auto" : "none") : ascii_lower(text(n, v));
       if (s == "auto")
         o.colour = true;
       else if (s == "none")
         o.colour = false;
       else
         bad_value(n, v, "auto or none");
     }},
    {"dpi", "N",
     "resolution of the printed colour, dots per inch (50 to 1200); later pages print lower when "
     "the time limit would pass (warning colour_resolution_lowered)",
     [](JobOptions& o, const std::string& n, const json& v) { o.dpi = number(n, v); }},
    {"overview", "",
     "with layout fit, a first page mapping the sheets, the pieces on each, the model as built "
     "(two views, each piece numbered) and the build order (unset: when there is more than one "
     "piece); left out on paper too small for it (warning overview_left_out)",
     [](JobOptions& o, const std::string& n, const json& v) { o.overview = boolean(n, v); }},
    {"title", "TEXT",
     "the kit's name, printed on every page beside its number (\"Duck \u00b7 page 2 of 5\"), as "
     "the overview's title and as the PDF's title: at most 80 characters (unset: none)",
     [](JobOptions& o, const std::string& n, const json& v) { o.title = title(n, v); }},
    {"components", "all|largest",
     "all: every connected part of the mesh its own piece; largest: only the largest part",
     [](JobOptions& o, const std::string& n, const json& v) {
       const std::string s = ascii_lower(text(n, v));
       if (s == "all")
         o.components = Components::All;
       else if (s == "largest")
         o.components = Components::Largest;
       else
         bad_value(n, v, "all or largest");
     }},
    {"strict", "",
     "refuse a mesh that needs repair (non-manifold edges, pinched vertices, degenerate or "
     "flipped faces, several parts) instead of repairing it",
     [](JobOptions& o, const std::string& n, const json& v) { o.strict = boolean(n, v); }},
    {"callback_url", "URL",
     "service only: POST the job's final status, signed, to this http:// URL when the job "
     "ends (its host must be allowed by the server's --webhook-hosts)",
     [](JobOptions& o, const std::string& n, const json& v) {
       o.callback_url = text(n, v);
       parse_callback_url(*o.callback_url);
     }},
};

const Spec* find_option(std::string_view name) {
  for (const Spec& s : kOptions)
    if (name == s.name) return &s;
  return nullptr;
}

const Spec* find_flag(std::string_view flag) {
  for (const Spec& s : kOptions)
    if (flag == option_flag(s.name)) return &s;
  return nullptr;
}

bool is_length(const Spec& spec) { return std::string_view(spec.name).ends_with("_mm"); }

void apply(JobOptions& o, const std::string& name, const json& v) {
  if (const Spec* spec = find_option(name)) return spec->apply(o, name, v);
  std::string known;
  for (const Spec& s : kOptions) known += std::string(known.empty() ? "" : ", ") + s.name;
  throw InvalidOptionException("unknown_option", name,
                               "unknown option '" + name + "' (known: " + known + ")");
}

void range(bool ok, const std::string& name, const std::string& message) {
  if (!ok)
    throw InvalidOptionException("option_out_of_range", name, "option '" + name + "' " + message);
}

bool within(double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; }

}  // namespace

std::string detail_name(const Detail& detail) {
  switch (detail.mode) {
    case DetailMode::Auto:
      return "auto";
    case DetailMode::Full:
      return "full";
    case DetailMode::Faces:
      break;
  }
  return std::to_string(detail.faces);
}

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
    case Strategy::AUTO:
      return "AUTO";
  }
  return "AUTO";
}

std::string option_flag(std::string_view name) {
  std::string flag =
      "--" + std::string(name.ends_with("_mm") ? name.substr(0, name.size() - 3) : name);
  std::replace(flag.begin() + 2, flag.end(), '_', '-');
  return flag;
}

bool is_boolean_flag(std::string_view flag) {
  const Spec* spec = find_flag(flag);
  return spec && std::string_view(spec->value).empty();
}

bool apply_option_flag(JobOptions& options, std::string_view flag,
                       std::optional<std::string_view> value) {
  const Spec* spec = find_flag(flag);
  if (!spec) return false;
  const std::string name = spec->name;
  if (std::string_view(spec->value).empty() && !value) {
    spec->apply(options, name, true);
    return true;
  }
  if (!value)
    throw InvalidOptionException("invalid_option_value", name,
                                 std::string(flag) + " needs a value (" + spec->value + ")");
  if (!is_length(*spec)) {
    spec->apply(options, name, std::string(*value));
    return true;
  }
  try {
    spec->apply(options, name, *value == "0" ? 0.0 : parse_length_mm(*value));
  } catch (const InvalidOptionException& e) {
    throw InvalidOptionException(e.code(), name, std::string(flag) + ": " + e.what());
  }
  return true;
}

std::string options_help() {
  constexpr std::size_t kColumn = 26;  // where the help starts
  const json defaults = options_to_json(JobOptions{});
  std::string out;
  for (const Spec& s : kOptions) {
    std::string left = "  " + option_flag(s.name) + " " + (*s.value ? s.value : "[yes|no]");
    if (left.size() >= kColumn) {  // a long flag: its help on the next line
      out += left + "\n";
      left.clear();
    }
    left.resize(kColumn, ' ');
    // The help and the default, wrapped at 100 columns, continued under itself.
    std::string help = s.help;
    const auto found = defaults.find(s.name);  // older names have no value of their own
    if (const json& d = found != defaults.end() ? *found : json(nullptr); !d.is_null()) {
      char number[32];
      if (d.is_number_float()) std::snprintf(number, sizeof number, "%g", d.get<double>());
      help += "; default " + (d.is_boolean()        ? std::string(d.get<bool>() ? "yes" : "no")
                              : d.is_string()       ? d.get<std::string>()
                              : d.is_number_float() ? std::string(number)
                                                    : json_text(d));
    }
    std::string line = left;
    for (std::string_view rest = help; !rest.empty();) {
      std::size_t take = rest.size();
      if (line.size() + take > 99) {
        take = rest.rfind(' ', 99 - line.size());
        if (take == std::string_view::npos || take == 0) take = rest.size();
      }
      out += line + std::string(rest.substr(0, take)) + "\n";
      rest.remove_prefix(std::min(rest.size(), take + 1));
      line = std::string(kColumn, ' ');
    }
  }
  return out;
}

namespace {
// A number of seconds as a person writes it: 600, 0.5, 1e+09 (std::to_string gave 600.000000).
std::string seconds(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}
}  // namespace

void validate_options(const JobOptions& o, const OptionsLimits& limits) {
  if (o.target_faces)
    range(*o.target_faces >= 4 && *o.target_faces <= limits.max_target_faces, "target_faces",
          "must be between 4 and " + std::to_string(limits.max_target_faces));
  if (o.detail.mode == DetailMode::Faces)
    range(o.detail.faces >= 4 && o.detail.faces <= limits.max_target_faces, "detail",
          "must be auto, full, or between 4 and " + std::to_string(limits.max_target_faces));
  if (o.time_limit)
    range(
        std::isfinite(*o.time_limit) && *o.time_limit > 0 && *o.time_limit <= limits.max_time_limit,
        "time_limit",
        "must be more than 0 and at most " + seconds(limits.max_time_limit) + " seconds");
  if (o.size_mm)
    range(std::isfinite(*o.size_mm) && *o.size_mm > 0 && *o.size_mm <= 100'000, "size_mm",
          "must be more than 0 and at most 100000 millimetres");
  if (o.scale)
    range(std::isfinite(*o.scale) && *o.scale > 0 && *o.scale <= 1e6, "scale",
          "must be more than 0 and at most 1e6 millimetres per unit");
  if (o.size_mm && o.scale)
    throw InvalidOptionException("conflicting_options", "scale",
                                 "options 'size_mm' and 'scale' both set the print size; give one");
  range(within(o.margin_mm, 0, 50), "margin_mm", "must be between 0 and 50 millimetres");
  range(within(o.overlap_mm, 0, 50), "overlap_mm", "must be between 0 and 50 millimetres");
  range(within(o.tab_height_mm, 0, 50), "tab_height_mm", "must be between 0 and 50 millimetres");
  range(within(o.min_tab_height_mm, 0, 50), "min_tab_height_mm",
        "must be between 0 and 50 millimetres");
  range(o.tab_room_budget <= kMaxTabRoomBudget, "tab_room_budget",
        "must be at most " + std::to_string(kMaxTabRoomBudget) + " moves");
  range(o.merge_budget <= kMaxMergeBudget, "merge_budget",
        "must be at most " + std::to_string(kMaxMergeBudget) + " tests");
  range(within(o.dpi, kMinColourDpi, kMaxColourDpi), "dpi",
        "must be between 50 and 1200 dots per inch");
  range(std::isfinite(o.flat_fold_degrees) && o.flat_fold_degrees >= 0 && o.flat_fold_degrees < 90,
        "flat_fold_degrees", "must be at least 0 and less than 90 degrees");
  // What the print checks of itself: a custom paper too small for its margins, say.
  print_options(o).validate();
  page_options(o).validate();
}

JobOptions parse_options_query(const std::multimap<std::string, std::string>& params,
                               const OptionsLimits& limits) {
  JobOptions options;
  for (auto it = params.begin(); it != params.end(); ++it) {
    if (params.count(it->first) > 1)
      throw InvalidOptionException("invalid_option_value", it->first,
                                   "option '" + it->first + "' is given more than once");
    apply(options, it->first, json(it->second));
  }
  validate_options(options, limits);
  return options;
}

JobOptions parse_options_json(std::string_view text, const OptionsLimits& limits) {
  if (text.size() > kMaxOptionsJsonBytes)
    throw InvalidOptionException("malformed_options", "",
                                 "the options part has " + std::to_string(text.size()) +
                                     " bytes; at most " + std::to_string(kMaxOptionsJsonBytes) +
                                     " are accepted");
  if (json_depth(text) > kMaxOptionsJsonDepth)
    throw InvalidOptionException(
        "malformed_options", "",
        "the options part nests deeper than " + std::to_string(kMaxOptionsJsonDepth) + " levels");
  const json doc = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (doc.is_discarded())
    throw InvalidOptionException("malformed_options", "", "the options part is not valid JSON");
  if (!doc.is_object())
    throw InvalidOptionException("malformed_options", "", "the options part must be a JSON object");
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
              {"detail", o.detail.mode == DetailMode::Faces ? json(o.detail.faces)
                                                            : json(detail_name(o.detail))},
              {"time_limit", opt(o.time_limit)},
              {"size_mm", opt(o.size_mm)},
              {"scale", opt(o.scale)},
              {"paper", o.paper},
              {"margin_mm", o.margin_mm},
              {"overlap_mm", o.overlap_mm},
              {"layout", o.layout ? json(page_layout_name(*o.layout)) : json(nullptr)},
              {"prefer", fit_goal_name(o.prefer)},
              {"tabs", tab_mode_name(o.tabs)},
              {"tab_height_mm", o.tab_height_mm},
              {"min_tab_height_mm", o.min_tab_height_mm},
              {"tab_room_budget", o.tab_room_budget},
              {"merge_budget", o.merge_budget},
              {"flat_fold_degrees", o.flat_fold_degrees},
              {"labels", o.labels},
              {"colour", o.colour ? "auto" : "none"},
              {"dpi", o.dpi},
              {"overview", opt(o.overview)},
              {"title", o.title.empty() ? json(nullptr) : json(o.title)},
              {"components", o.components == Components::All ? "all" : "largest"},
              {"strict", o.strict},
              {"callback_url", opt(o.callback_url)}};
}

PrintOptions print_options(const JobOptions& o) {
  PrintOptions print;
  if (o.size_mm) print.size_mm = *o.size_mm;
  if (o.scale) print.scale = *o.scale;
  print.flat_fold_degrees = o.flat_fold_degrees;
  print.tabs = o.tabs;
  print.tab_height_mm = o.tab_height_mm;
  print.min_tab_height_mm = o.min_tab_height_mm;
  print.tab_room_budget = o.tab_room_budget;
  print.merge_budget = o.merge_budget;
  print.prefer = o.prefer;
  print.labels = o.labels;
  return print;
}

bool has_paper(const JobOptions& o) { return o.paper != "none"; }

PageOptions page_options(const JobOptions& o) {
  PageOptions page;
  if (has_paper(o)) page.paper = parse_paper(o.paper);
  page.margin_mm = o.margin_mm;
  page.overlap_mm = o.overlap_mm;
  return page;
}

}  // namespace papernet
