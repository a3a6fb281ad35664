#include "server/job.h"

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
