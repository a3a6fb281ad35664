// The service's front: submitting, looking at and cancelling jobs (HTTP threads). The workers'
// side, claiming and running jobs under leases, is job_workers.cpp.
#include "server/job_service.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/io/json_text.h"
#include "server/internal/live_job.h"
#include "server/problem.h"

namespace papernet::server {
namespace {

std::uint64_t fnv1a(std::uint64_t h, std::string_view bytes) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

// host-pid-tag: the tag tells two lives of one container (both pid 1) apart.
std::string default_node_name() {
  char host[256] = "papernet";
  gethostname(host, sizeof host - 1);
  return std::string(host) + "-" + std::to_string(getpid()) + "-" + new_job_id().substr(0, 4);
}

IntermediateLevel level_of(const JobOutput& output) {
  IntermediateLevel level{output.faces, output.input_faces, output.overlaps, {}};
  for (const auto& [name, file] : output.files) level.files.push_back(name);
  return level;
}

}  // namespace

std::string job_input_key(const JobInput& input, const JobOptions& options) {
  // Two independent 64-bit FNV-1a streams; the store confirms a match byte for byte.
  std::uint64_t a = 0xcbf29ce484222325ULL, b = 0x84222325cbf29ce4ULL;
  auto feed = [&](std::string_view part) {
    const std::string size = std::to_string(part.size()) + ":";
    a = fnv1a(fnv1a(a, size), part);
    b = fnv1a(fnv1a(b, part), size);
  };
  feed(format_name(input.format));
  feed(input.mesh);
  for (const auto& [name, data] : input.external_files) {
    feed(name);
    feed(data);
  }
  // Where the result is announced is no part of what the result is: jobs that differ only in
  // their callback_url share results.
  nlohmann::json canonical = options_to_json(options);
  canonical.erase("callback_url");
  feed(json_text(canonical));
  char text[33];
  std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(a),
                static_cast<unsigned long long>(b));
  return text;
}

JobService::JobService(JobStore& store, JobRunner runner, ServiceSettings settings, Logger log)
    : store_(store),
      runner_(std::move(runner)),
      settings_(std::move(settings)),
      log_(std::move(log)),
      buckets_{0.1, 0.5, 1, 2, 5, 10, 30, 60, 120, 300, 600},
      bucket_counts_(buckets_.size() + 1, 0) {
  if (settings_.node.empty()) settings_.node = default_node_name();
}

JobService::~JobService() { shutdown(std::chrono::milliseconds(0)); }

JobRecord JobService::submit(JobInput input, JobOptions options, const Submitter& by) {
  const std::string& tenant = by.tenant;
  if (!accepting_) throw ApiError("shutting_down", "the server is shutting down; try again");
  if (!options.time_limit) options.time_limit = settings_.default_time_limit;
  JobRecord job;
  job.id = by.job_id.empty() ? new_job_id() : by.job_id;
  job.tenant = tenant;
  job.created = now_seconds();
  job.options = options_to_json(options);
  job.format = format_name(input.format);
  job.input_bytes = input.mesh.size();
  for (const auto& [name, data] : input.external_files) job.input_bytes += data.size();
  job.input_key = job_input_key(input, options);

  if (settings_.reuse_results) {
    if (auto prior = store_.find_reusable(tenant, job.input_key, input)) {
      job.status = prior->status;
      job.started = job.finished = job.created;
      job.input_faces = prior->input_faces;
      job.faces = prior->faces;
      job.overlaps = prior->overlaps;
      job.result_kind = prior->result_kind;
      job.metrics = prior->metrics;
      job.metrics["reused_from"] = prior->id;
      job.result_job = prior->result_job;
      store_.insert(job, nullptr, 0);
      log_("job " + job.id + " -> " + status_name(job.status) + " (reused " + prior->id + ")");
      return job;
    }
  }
  if (by.queue_share < 1) {
    const auto share = std::max<std::size_t>(
        1, static_cast<std::size_t>(by.queue_share * static_cast<double>(settings_.queue_length)));
    if (store_.queued_count(tenant) >= share) {
      Problem p = make_problem(
          "queue_full", "this tenant's share of the queue (" + std::to_string(share) + " of " +
                            std::to_string(settings_.queue_length) + " jobs) is full; retry later");
      p.retry_after = static_cast<int>(retry_after_seconds(share));
      throw ApiError(p);
    }
  }
  if (!store_.insert(job, &input, settings_.queue_length)) {
    Problem p = make_problem(
        "queue_full",
        "the job queue is full (" + std::to_string(settings_.queue_length) + " jobs); retry later");
    p.retry_after = static_cast<int>(retry_after_seconds(settings_.queue_length));
    throw ApiError(p);
  }
  log_("job " + job.id + " -> queued (" + job.format + ", " + std::to_string(job.input_bytes) +
       " bytes)");
  {
    std::lock_guard lock(mutex_);
    ++wakeups_;
    ++version_;
  }
  work_cv_.notify_one();
  change_cv_.notify_all();
  return job;
}

std::optional<JobView> JobService::view(const std::string& id, const std::string* tenant) {
  std::optional<JobRecord> record = store_.find(id);
  if (!record || (tenant && record->tenant != *tenant)) return std::nullopt;
  JobView view{std::move(*record), std::nullopt, 0, false, std::nullopt, {}, std::nullopt};
  const JobRecord& r = view.record;
  if (const auto url = r.options.find("callback_url"); url != r.options.end() && url->is_string())
    view.callback = store_.webhook(id);
  if (is_final(r.status)) {
    view.result_files = r.result_files;
    return view;
  }
  view.cancel_requested = r.cancel_requested;
  if (r.status == JobStatus::Queued) {
    view.queue_position = store_.queue_position(r.seq);
    return view;
  }
  {
    std::lock_guard lock(mutex_);
    auto it = live_.find(id);
    if (it != live_.end() && it->second->claim.node == r.node &&
        it->second->claim.attempt == r.attempts) {
      const Live& live = *it->second;
      view.progress = live.progress;
      view.cancel_requested = view.cancel_requested || live.cancel;
      if (live.intermediate) view.intermediate = level_of(*live.intermediate);
      return view;
    }
  }
  // Running on another node: what it published.
  view.progress = progress_from_json(r.progress);
  view.intermediate = intermediate_level_from_json(r.intermediate);
  return view;
}

std::optional<IntermediateFile> JobService::intermediate(const std::string& id,
                                                         const std::string& name) {
  {
    std::lock_guard lock(mutex_);
    if (auto it = live_.find(id); it != live_.end()) {
      const std::shared_ptr<const JobOutput> output = it->second->intermediate;
      if (!output) return std::nullopt;
      auto file = output->files.find(name);
      if (file == output->files.end()) return std::nullopt;
      return IntermediateFile{file->second, output->faces, output->input_faces};
    }
  }
  return store_.intermediate(id, name);
}

JobView JobService::cancel(const std::string& id) {
  std::optional<JobRecord> record = store_.find(id);
  if (!record) throw ApiError("job_not_found", "no job " + id);
  if (!is_final(record->status)) {
    const CancelOutcome outcome = store_.cancel(
        id, problem_json(make_problem("job_cancelled", "cancelled while queued")), now_seconds());
    {
      std::lock_guard lock(mutex_);
      if (outcome == CancelOutcome::Requested)
        if (auto it = live_.find(id); it != live_.end()) it->second->cancel = true;
      ++version_;
    }
    change_cv_.notify_all();
    if (outcome == CancelOutcome::Cancelled) log_("job " + id + " queued -> cancelled");
    if (outcome != CancelOutcome::NotActive)
      if (auto v = view(id)) return *v;
    record = store_.find(id);  // it ended in the meantime
    if (!record) throw ApiError("job_not_found", "no job " + id);
  }
  throw ApiError("job_finished", "job " + id + " already " + status_name(record->status));
}

std::uint64_t JobService::wait_for_change(std::uint64_t seen, std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  change_cv_.wait_for(lock, timeout, [&] { return version_ != seen || stop_; });
  return version_;
}

std::uint64_t JobService::version() {
  std::lock_guard lock(mutex_);
  return version_;
}

void JobService::shutdown(std::chrono::milliseconds grace) {
  accepting_ = false;
  {
    std::unique_lock lock(mutex_);
    draining_ = true;
    if (!live_.empty()) log_("shutdown: waiting for running jobs");
    change_cv_.wait_for(lock, grace, [&] { return live_.empty(); });
    abort_running_ = true;
    stop_ = true;
  }
  work_cv_.notify_all();
  change_cv_.notify_all();
  for (std::thread& t : workers_)
    if (t.joinable()) t.join();
  workers_.clear();
  {
    std::lock_guard lock(mutex_);
    keeper_stop_ = true;
  }
  keeper_cv_.notify_all();
  if (keeper_.joinable()) keeper_.join();
  store_.listen({});
}

ServiceStats JobService::stats() {
  ServiceStats s;
  s.store_kind = store_.kind();
  try {
    s.jobs_by_status = store_.count_by_status();
    s.queued_by_tenant = store_.queued_by_tenant();
    s.stored_bytes = store_.stored_bytes();
  } catch (const StoreError&) {
    s.store_up = false;
  }
  if (auto it = s.jobs_by_status.find("queued"); it != s.jobs_by_status.end())
    s.queued = it->second;
  s.store = store_.stats();
  std::lock_guard lock(mutex_);
  s.running = live_.size();
  s.duration_buckets = buckets_;
  s.duration_counts = bucket_counts_;
  s.duration_sum = duration_sum_;
  s.duration_count = duration_count_;
  s.claims = claims_;
  s.lease_expiries = lease_expiries_;
  s.leases_lost = leases_lost_;
  return s;
}

std::size_t JobService::retry_after_seconds(std::size_t queued) {
  std::lock_guard lock(mutex_);
  const double mean = duration_count_ ? duration_sum_ / static_cast<double>(duration_count_) : 5;
  const double wait = mean * static_cast<double>(queued) /
                      static_cast<double>(std::max<std::size_t>(1, settings_.workers));
  return static_cast<std::size_t>(std::clamp(std::ceil(wait), 1.0, 600.0));
}

}  // namespace papernet::server
