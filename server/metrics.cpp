#include "server/metrics.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <sstream>

namespace papernet::server {

void HttpMetrics::count(int status, double seconds) {
  std::lock_guard lock(mutex_);
  ++by_status_[status];
  seconds_ += seconds;
}

std::map<int, std::uint64_t> HttpMetrics::by_status() const {
  std::lock_guard lock(mutex_);
  return by_status_;
}

double HttpMetrics::seconds_total() const {
  std::lock_guard lock(mutex_);
  return seconds_;
}

std::string render_metrics(const ServiceStats& jobs, const HttpMetrics& http) {
  std::ostringstream out;
  out << "# HELP papernet_queue_length Jobs waiting for a worker (of every node).\n"
         "# TYPE papernet_queue_length gauge\n"
      << "papernet_queue_length " << jobs.queued << "\n"
      << "# HELP papernet_jobs_running Jobs a worker is running now.\n"
         "# TYPE papernet_jobs_running gauge\n"
      << "papernet_jobs_running " << jobs.running << "\n"
      << "# HELP papernet_jobs Jobs in the store by status.\n"
         "# TYPE papernet_jobs gauge\n";
  for (const char* status :
       {"queued", "running", "succeeded", "approximated", "failed", "cancelled"}) {
    auto it = jobs.jobs_by_status.find(status);
    out << "papernet_jobs{status=\"" << status << "\"} "
        << (it == jobs.jobs_by_status.end() ? 0 : it->second) << "\n";
  }
  out << "# HELP papernet_store_up Whether the job store answered (" << jobs.store_kind
      << ").\n"
         "# TYPE papernet_store_up gauge\n"
      << "papernet_store_up " << (jobs.store_up ? 1 : 0) << "\n"
      << "# HELP papernet_store_claims_total Jobs this node's workers claimed from the queue.\n"
         "# TYPE papernet_store_claims_total counter\n"
      << "papernet_store_claims_total " << jobs.claims << "\n"
      << "# HELP papernet_store_lease_expiries_total Claims of running jobs whose node's lease "
         "had expired.\n"
         "# TYPE papernet_store_lease_expiries_total counter\n"
      << "papernet_store_lease_expiries_total " << jobs.lease_expiries << "\n"
      << "# HELP papernet_store_leases_lost_total Jobs running here whose lease passed to "
         "another node.\n"
         "# TYPE papernet_store_leases_lost_total counter\n"
      << "papernet_store_leases_lost_total " << jobs.leases_lost << "\n"
      << "# HELP papernet_store_reconnects_total Connections to the database made again after "
         "one was lost.\n"
         "# TYPE papernet_store_reconnects_total counter\n"
      << "papernet_store_reconnects_total " << jobs.store.reconnects << "\n";
  out << "# HELP papernet_job_duration_seconds Time from start to end of finished jobs.\n"
         "# TYPE papernet_job_duration_seconds histogram\n";
  for (std::size_t i = 0; i < jobs.duration_buckets.size(); ++i)
    out << "papernet_job_duration_seconds_bucket{le=\"" << jobs.duration_buckets[i] << "\"} "
        << jobs.duration_counts[i] << "\n";
  out << "papernet_job_duration_seconds_bucket{le=\"+Inf\"} "
      << (jobs.duration_counts.empty() ? 0 : jobs.duration_counts.back()) << "\n"
      << "papernet_job_duration_seconds_sum " << jobs.duration_sum << "\n"
      << "papernet_job_duration_seconds_count " << jobs.duration_count << "\n"
      << "# HELP papernet_http_requests_total HTTP requests answered, by status code.\n"
         "# TYPE papernet_http_requests_total counter\n";
  for (const auto& [status, n] : http.by_status())
    out << "papernet_http_requests_total{status=\"" << status << "\"} " << n << "\n";
  out << "# HELP papernet_http_request_seconds_total Time spent answering HTTP requests.\n"
         "# TYPE papernet_http_request_seconds_total counter\n"
      << "papernet_http_request_seconds_total " << http.seconds_total() << "\n";
  return out.str();
}

void log_line(std::string_view line) {
  static std::mutex mutex;
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  gmtime_r(&t, &tm);
  char stamp[64];
  std::snprintf(stamp, sizeof stamp, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900,
                tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>(ms));
  std::lock_guard lock(mutex);
  std::cerr << stamp << " " << line << std::endl;
}

}  // namespace papernet::server
