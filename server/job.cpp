#include "server/job.h"

#include <algorithm>
#include <chrono>
#include <random>
#include <stdexcept>

namespace papernet::server {

std::string status_name(JobStatus status) {
  switch (status) {
    case JobStatus::Queued:
      return "queued";
    case JobStatus::Running:
      return "running";
    case JobStatus::Succeeded:
      return "succeeded";
    case JobStatus::Approximated:
      return "approximated";
    case JobStatus::Failed:
      return "failed";
    case JobStatus::Cancelled:
      return "cancelled";
  }
  return "failed";
}

JobStatus parse_status(const std::string& name) {
  for (JobStatus s : {JobStatus::Queued, JobStatus::Running, JobStatus::Succeeded,
                      JobStatus::Approximated, JobStatus::Failed, JobStatus::Cancelled})
    if (status_name(s) == name) return s;
  throw std::invalid_argument("unknown job status '" + name + "'");
}

bool is_final(JobStatus status) {
  return status != JobStatus::Queued && status != JobStatus::Running;
}

std::vector<std::string> split_file_names(const std::string& joined) {
  std::vector<std::string> names;
  for (std::size_t from = 0; from < joined.size();) {
    const auto end = std::min(joined.find('/', from), joined.size());
    names.push_back(joined.substr(from, end - from));
    from = end + 1;
  }
  std::sort(names.begin(), names.end());
  return names;
}

MeshFormat format_of_record(const std::string& name) {
  return name == "unknown" ? MeshFormat::Unknown : format_from_extension("x." + name);
}

nlohmann::json progress_to_json(const ProgressInfo& info) {
  return {{"phase", info.phase},
          {"faces", info.faces},
          {"input_faces", info.input_faces},
          {"overlaps", info.overlaps},
          {"iterations", info.iterations},
          {"elapsed_seconds", info.elapsed_seconds},
          {"piece", info.piece},
          {"pieces", info.pieces},
          {"fraction", info.fraction}};
}

std::optional<ProgressInfo> progress_from_json(const nlohmann::json& doc) {
  if (!doc.is_object() || !doc.contains("phase")) return std::nullopt;
  ProgressInfo info;
  info.phase = doc.value("phase", "");
  info.faces = doc.value("faces", std::size_t{0});
  info.input_faces = doc.value("input_faces", std::size_t{0});
  info.overlaps = doc.value("overlaps", std::size_t{0});
  info.iterations = doc.value("iterations", std::size_t{0});
  info.elapsed_seconds = doc.value("elapsed_seconds", 0.0);
  info.piece = doc.value("piece", std::size_t{0});
  info.pieces = doc.value("pieces", std::size_t{0});
  info.fraction = doc.value("fraction", 0.0);
  return info;
}

nlohmann::json intermediate_level_json(const JobOutput& output) {
  nlohmann::json files = nlohmann::json::array();
  for (const auto& [name, file] : output.files) files.push_back(name);
  return {{"faces", output.faces},
          {"input_faces", output.input_faces},
          {"overlaps", output.overlaps},
          {"files", files}};
}

std::optional<IntermediateLevel> intermediate_level_from_json(const nlohmann::json& doc) {
  if (!doc.is_object() || !doc.contains("files")) return std::nullopt;
  IntermediateLevel level;
  level.faces = doc.value("faces", std::size_t{0});
  level.input_faces = doc.value("input_faces", std::size_t{0});
  level.overlaps = doc.value("overlaps", std::size_t{0});
  for (const auto& name : doc["files"]) level.files.push_back(name.get<std::string>());
  return level;
}

std::string new_job_id() {
  thread_local std::mt19937_64 rng{std::random_device{}() ^
                                   (std::uint64_t{std::random_device{}()} << 32)};
  static constexpr char kHex[] = "0123456789abcdef";
  std::string id(32, '0');
  for (int half = 0; half < 2; ++half) {
    std::uint64_t bits = rng();
    for (int i = 0; i < 16; ++i, bits >>= 4) id[half * 16 + i] = kHex[bits & 15];
  }
  return id;
}

bool valid_job_id(std::string_view id) {
  if (id.size() != 32) return false;
  for (char c : id)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace papernet::server
