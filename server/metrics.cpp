#include "server/metrics.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <sstream>

namespace papernet::server {

namespace {

// Requests: from a cached status poll to an upload of many megabytes.
const std::vector<double> kRequestBounds = {0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25,
                                            0.5,   1,      2.5,   5,    10,    30,   120};
// Event streams last as long as their job, or until the client leaves.
const std::vector<double> kStreamBounds = {1, 10, 30, 60, 120, 300, 600, 1800, 3600};

Histogram histogram(const std::vector<double>& bounds) {
  Histogram h;
  h.bounds = bounds;
  h.counts.assign(bounds.size() + 1, 0);
  return h;
}

// A label value as the exposition format wants it: backslash, quote and newline escaped.
std::string label(const std::string& value) {
  std::string out;
  for (const char c : value) {
    if (c == '\\' || c == '"') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out;
}

void render_histogram(std::ostringstream& out, const std::string& name, const std::string& labels,
                      const Histogram& h) {
  std::uint64_t cumulative = 0;
  const std::string sep = labels.empty() ? "" : ",";
  for (std::size_t i = 0; i < h.counts.size(); ++i) {
    cumulative += h.counts[i];
    out << name << "_bucket{" << labels << sep << "le=\"";
    if (i < h.bounds.size())
      out << h.bounds[i];
    else
      out << "+Inf";
    out << "\"} " << cumulative << "\n";
  }
  std::string braces;
  if (!labels.empty()) {
    braces = "{";
    braces += labels;
    braces += "}";
  }
  out << name << "_sum" << braces << " " << h.sum << "\n"
      << name << "_count" << braces << " " << h.count << "\n";
}

}  // namespace

void Histogram::add(double seconds) {
  std::size_t i = 0;
  while (i < bounds.size() && seconds > bounds[i]) ++i;
  ++counts[i];
  sum += seconds;
  ++count;
}

std::string route_of(const std::string& method, const std::string& path) {
  std::string m = method;
  if (m != "GET" && m != "HEAD" && m != "POST" && m != "PUT" && m != "DELETE" && m != "PATCH" &&
      m != "OPTIONS")
    m = "OTHER";
  m += ' ';
  for (const char* fixed : {"/healthz", "/readyz", "/metrics", "/v1/openapi.json", "/v1/jobs"})
    if (path == fixed) return m + fixed;
  const std::string jobs = "/v1/jobs/";
  if (path.rfind(jobs, 0) == 0) {
    const std::size_t slash = path.find('/', jobs.size());
    if (slash == std::string::npos) return m + "/v1/jobs/{id}";
    const std::string rest = path.substr(slash + 1);
    if (rest == "events") return m + "/v1/jobs/{id}/events";
    for (const char* file : {"net.json", "net.svg", "net.pdf", "mesh.glb"})
      if (rest == file) return m + "/v1/jobs/{id}/{file}";
    for (const std::string list : {"textures", "pages"})
      if (rest.size() > list.size() + 1 && rest.starts_with(list + "/") &&
          rest.find_first_not_of("0123456789", list.size() + 1) == std::string::npos)
        return m + "/v1/jobs/{id}/" + list + "/{k}";
  }
  return m + "other";
}

void HttpMetrics::count(const std::string& route, int status, const std::string& code,
                        double seconds) {
  std::lock_guard lock(mutex_);
  ++by_status_[status];
  seconds_ += seconds;
  if (route == kEventsRoute) {
    if (streams_.bounds.empty()) streams_ = histogram(kStreamBounds);
    streams_.add(seconds);
  } else {
    auto [it, added] = by_route_.try_emplace(route);
    if (added) it->second = histogram(kRequestBounds);
    it->second.add(seconds);
  }
  if (status >= 400) ++failures_[{status, code}];
}

std::map<std::string, Histogram> HttpMetrics::by_route() const {
  std::lock_guard lock(mutex_);
  return by_route_;
}

Histogram HttpMetrics::streams() const {
  std::lock_guard lock(mutex_);
  return streams_.bounds.empty() ? histogram(kStreamBounds) : streams_;
}

std::map<std::pair<int, std::string>, std::uint64_t> HttpMetrics::failures() const {
  std::lock_guard lock(mutex_);
  return failures_;
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
      << "# HELP papernet_store_bytes Bytes of uploads, intermediates and results in the store "
         "(what retention and --max-store remove).\n"
         "# TYPE papernet_store_bytes gauge\n"
      << "papernet_store_bytes " << jobs.stored_bytes << "\n"
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
  out << "# HELP papernet_http_request_duration_seconds Time to answer a request, by route "
         "(event streams apart).\n"
         "# TYPE papernet_http_request_duration_seconds histogram\n";
  for (const auto& [route, h] : http.by_route()) {
    std::string labels = "route=\"";
    labels += label(route);
    labels += '"';
    render_histogram(out, "papernet_http_request_duration_seconds", labels, h);
  }
  out << "# HELP papernet_http_stream_duration_seconds How long event streams stayed open.\n"
         "# TYPE papernet_http_stream_duration_seconds histogram\n";
  render_histogram(out, "papernet_http_stream_duration_seconds", "", http.streams());
  out << "# HELP papernet_http_open_streams Event streams open now.\n"
         "# TYPE papernet_http_open_streams gauge\n"
      << "papernet_http_open_streams " << http.open_streams.load() << "\n"
      << "# HELP papernet_http_failures_total Requests answered 4xx or 5xx, by status and "
         "problem code.\n"
         "# TYPE papernet_http_failures_total counter\n";
  for (const auto& [key, n] : http.failures())
    out << "papernet_http_failures_total{status=\"" << key.first << "\",code=\""
        << label(key.second.empty() ? "none" : key.second) << "\"} " << n << "\n";
  out << "# HELP papernet_tenant_queue_length Jobs waiting for a worker, by tenant (\"\" without "
         "API keys).\n"
         "# TYPE papernet_tenant_queue_length gauge\n";
  for (const auto& [tenant, n] : jobs.queued_by_tenant)
    out << "papernet_tenant_queue_length{tenant=\"" << label(tenant) << "\"} " << n << "\n";
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
