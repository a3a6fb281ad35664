#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <string_view>

#include "server/job_service.h"

namespace papernet::server {

/// Requests served, by status code, and their total time. Thread-safe.
class HttpMetrics {
 public:
  void count(int status, double seconds);
  std::map<int, std::uint64_t> by_status() const;
  double seconds_total() const;

 private:
  mutable std::mutex mutex_;
  std::map<int, std::uint64_t> by_status_;
  double seconds_ = 0;
};

/// The Prometheus text exposition (version 0.0.4) of everything /metrics reports.
std::string render_metrics(const ServiceStats& jobs, const HttpMetrics& http);

/// Writes one line to stderr, prefixed with the UTC time; lines never interleave.
void log_line(std::string_view line);

}  // namespace papernet::server
