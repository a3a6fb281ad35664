#include "server/job_json.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string_view>

#include "server/problem.h"

namespace papernet::server {

using nlohmann::json;

const std::vector<std::string>& result_file_names() {
  static const std::vector<std::string> names = {"net.json", "net.svg", "net.pdf", "mesh.glb"};
  return names;
}

std::string texture_file_name(std::size_t index) {
  std::string name = "texture-";
  name += std::to_string(index);
  return name;
}

std::string page_file_name(std::size_t number) {
  std::string name = "page-";
  name += std::to_string(number);
  name += ".svg";
  return name;
}

std::string content_disposition(const json& options, const std::string& file,
                                const std::string& content_type) {
  std::string name = file;
  if (file.rfind("texture-", 0) == 0)
    name += content_type == "image/png" ? ".png" : content_type == "image/jpeg" ? ".jpg" : "";
  const auto title = options.find("title");
  if (title != options.end() && title->is_string() && !title->get<std::string>().empty()) {
    // The title (validated: UTF-8 without control characters) with the characters no file
    // system takes in a name made "_", and no leading dot (a hidden file).
    std::string kit;
    for (const char c : title->get<std::string>())
      kit.push_back(std::string_view("/\\:*?\"<>|").find(c) == std::string_view::npos ? c : '_');
    if (kit[0] == '.') kit[0] = '_';
    const std::size_t dot = file.rfind('.');
    if (file.rfind("page-", 0) == 0)
      name = kit + " - page " + file.substr(5, dot - 5) + file.substr(dot);
    else if (file.rfind("texture-", 0) == 0)
      name = kit + " - " + name;
    else
      name = kit + file.substr(dot);
  }
  std::string ascii, encoded;
  bool plain = true;
  for (const char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x80) {
      plain = false;
      if ((c & 0xC0) != 0x80) ascii.push_back('_');  // one per letter, not per byte
    } else {
      ascii.push_back(ch);
    }
    if ((c < 0x80 && std::isalnum(c)) ||
        std::string_view("!#$&+-.^_`|~").find(ch) != std::string_view::npos) {
      encoded.push_back(ch);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      encoded += hex;
    }
  }
  std::string out = "inline; filename=\"" + ascii + "\"";
  if (!plain) out += "; filename*=UTF-8''" + encoded;
  return out;
}

namespace {

// Entry `index` of the array `links[list]`, served at `self`/`list`/`number`.
void add_listed_link(json& links, const std::string& self, const char* list, std::size_t index,
                     const std::string& number) {
  json& entries = links[list];
  if (!entries.is_array()) entries = json::array();
  while (entries.size() <= index) entries.push_back(nullptr);
  std::string link = self;
  link += '/';
  link += list;
  link += '/';
  link += number;
  entries[index] = std::move(link);
}

// A result file's link: its name; for a texture ("texture-k") entry k of "textures", served at
// /v1/jobs/{id}/textures/{k}; for a page ("page-k.svg") entry k - 1 of "pages", served at
// /v1/jobs/{id}/pages/{k}.
void add_link(json& links, const std::string& self, const std::string& name) {
  if (name.starts_with("texture-")) {
    const std::string k = name.substr(8);
    add_listed_link(links, self, "textures", std::stoul(k), k);
  } else if (name.starts_with("page-") && name.ends_with(".svg")) {
    const std::string k = name.substr(5, name.size() - 9);
    add_listed_link(links, self, "pages", std::stoul(k) - 1, k);
  } else {
    links[name] = self + "/" + name;
  }
}

}  // namespace

json iso_time(double seconds) {
  if (seconds <= 0) return nullptr;
  const auto whole = static_cast<std::time_t>(std::floor(seconds));
  const int ms = static_cast<int>((seconds - static_cast<double>(whole)) * 1000);
  std::tm tm{};
  gmtime_r(&whole, &tm);
  char text[64];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900,
                tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, ms);
  return text;
}

json job_to_json(const JobView& view, double now) {
  const JobRecord& r = view.record;
  const std::string self = "/v1/jobs/" + r.id;
  json doc = {{"id", r.id},
              {"status", status_name(r.status)},
              {"created", iso_time(r.created)},
              {"started", iso_time(r.started)},
              {"finished", iso_time(r.finished)},
              {"input",
               {{"format", r.format},
                {"bytes", r.input_bytes},
                {"faces", r.input_faces ? json(r.input_faces) : json(nullptr)}}},
              {"options", r.options}};

  double elapsed = 0;
  if (r.started > 0) elapsed = (r.finished > 0 ? r.finished : now) - r.started;
  json progress = {
      // A job a worker claimed that has not reported yet is loading its input.
      {"phase", r.status == JobStatus::Running ? std::string("load") : status_name(r.status)},
      {"faces", nullptr},
      {"input_faces", r.input_faces ? json(r.input_faces) : json(nullptr)},
      {"overlaps", nullptr},
      {"iterations", nullptr},
      {"elapsed_seconds", std::round(elapsed * 1000) / 1000},
      // Of the whole job: 0 until it reports, 1 once it ended (also when it failed).
      {"fraction", is_final(r.status) ? 1.0 : 0.0},
      {"queue_position", view.queue_position ? json(view.queue_position) : json(nullptr)}};
  if (view.progress) {
    progress["phase"] = view.progress->phase;
    // Rounded down, and under 1 until the job has ended: the run reports 1 when its last
    // document is written, before the job stores its results and ends (an event stream showed
    // a running job at 1 in between, 2026-11-29).
    progress["fraction"] = is_final(r.status)
                               ? 1.0
                               : std::min(0.999, std::floor(view.progress->fraction * 1000) / 1000);
    progress["faces"] = view.progress->faces;
    progress["input_faces"] = view.progress->input_faces;
    progress["overlaps"] = view.progress->overlaps;
    progress["iterations"] = view.progress->iterations;
    if (view.progress->pieces > 0) {
      progress["piece"] = view.progress->piece;
      progress["pieces"] = view.progress->pieces;
    }
  } else if (is_final(r.status) && !r.result_kind.empty()) {
    progress["phase"] = "done";
    progress["faces"] = r.faces;
    progress["overlaps"] = r.overlaps;
  }
  doc["progress"] = progress;
  if (doc["input"]["faces"].is_null() && !progress["input_faces"].is_null() &&
      progress["input_faces"] != 0)
    doc["input"]["faces"] = progress["input_faces"];
  if (view.cancel_requested && !is_final(r.status)) doc["cancel_requested"] = true;

  json links = {{"self", self}, {"events", self + "/events"}};
  if (!r.result_kind.empty()) {
    json metrics = r.metrics;
    json repairs = metrics.contains("repairs") ? metrics["repairs"] : json::array();
    json pieces = metrics.contains("pieces") ? metrics["pieces"] : json::array();
    json warnings = metrics.contains("warnings") ? metrics["warnings"] : json::array();
    json detail = metrics.contains("detail") ? metrics["detail"] : json(nullptr);
    for (const char* lifted : {"repairs", "pieces", "warnings", "detail"}) metrics.erase(lifted);
    doc["result"] = {{"kind", r.result_kind},         {"faces", r.faces},
                     {"input_faces", r.input_faces},  {"overlaps", r.overlaps},
                     {"detail", std::move(detail)},   {"pieces", std::move(pieces)},
                     {"repairs", std::move(repairs)}, {"warnings", std::move(warnings)},
                     {"metrics", std::move(metrics)}};
    for (const std::string& name : view.result_files) add_link(links, self, name);
  } else {
    doc["result"] = nullptr;
  }
  if (view.intermediate) {
    doc["intermediate"] = {{"faces", view.intermediate->faces},
                           {"input_faces", view.intermediate->input_faces},
                           {"overlaps", view.intermediate->overlaps}};
    for (const std::string& name : view.intermediate->files) add_link(links, self, name);
  }
  doc["error"] = r.error.is_object() ? r.error : json(nullptr);
  if (view.callback) {
    json attempts = json::array();
    for (const json& a : view.callback->attempts) {
      json shown = a;
      shown["at"] = iso_time(a.value("at", 0.0));
      attempts.push_back(std::move(shown));
    }
    doc["callback"] = {
        {"url", view.callback->url},
        {"state", view.callback->state},
        {"delivered", view.callback->state == "delivered"},
        {"attempts", std::move(attempts)},
        {"next_attempt", view.callback->state == "pending" && view.callback->next_at > 0
                             ? iso_time(view.callback->next_at)
                             : json(nullptr)}};
  }
  doc["links"] = links;
  return doc;
}

}  // namespace papernet::server
