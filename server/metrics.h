#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "server/service_records.h"

namespace papernet::server {

/// A latency histogram: cumulative counts per upper bound, then +Inf.
struct Histogram {
  std::vector<double> bounds;
  std::vector<std::uint64_t> counts;  ///< one per bound, then +Inf; not cumulative
  double sum = 0;
  std::uint64_t count = 0;
  void add(double seconds);
};

/// Requests served: by status code, by route (a latency histogram; event streams in one of
/// their own, since a stream lasts as long as its job), failures (4xx, 5xx) by status and
/// problem code, and the event streams open now. Thread-safe.
class HttpMetrics {
 public:
  /// One answered request. `route` is route_of's; `code` the problem's code ("" for none).
  void count(const std::string& route, int status, const std::string& code, double seconds);
  std::map<int, std::uint64_t> by_status() const;
  double seconds_total() const;
  std::map<std::string, Histogram> by_route() const;
  Histogram streams() const;
  std::map<std::pair<int, std::string>, std::uint64_t> failures() const;

  /// Event streams open now (the HTTP API counts them, for its limit too).
  std::atomic<int> open_streams{0};

 private:
  mutable std::mutex mutex_;
  std::map<int, std::uint64_t> by_status_;
  double seconds_ = 0;
  std::map<std::string, Histogram> by_route_;
  Histogram streams_;
  std::map<std::pair<int, std::string>, std::uint64_t> failures_;
};

/// The route a request took, for metrics: "GET /v1/jobs/{id}" and the like, so that labels
/// stay few whatever clients send ("GET other" for the rest, "OTHER other" for odd methods).
std::string route_of(const std::string& method, const std::string& path);

/// The route label of event streams (their own histogram).
inline constexpr const char* kEventsRoute = "GET /v1/jobs/{id}/events";

/// The Prometheus text exposition (version 0.0.4) of everything /metrics reports.
std::string render_metrics(const ServiceStats& jobs, const HttpMetrics& http);

/// Writes one line to stderr, prefixed with the UTC time; lines never interleave.
void log_line(std::string_view line);

}  // namespace papernet::server
