#include "server/job_service.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "server/problem.h"

namespace papernet::server {

struct JobService::Live {
  JobStatus status = JobStatus::Queued;
  std::optional<ProgressInfo> progress;
  std::atomic<bool> cancel{false};
  std::shared_ptr<const JobOutput> intermediate;
};

// The hook a running job talks to. Cancellation: the client's DELETE, the hard time limit,
// or a server shutdown that outlived its grace period.
class JobService::Sink : public JobSink {
 public:
  Sink(JobService& service, std::shared_ptr<Live> live, double deadline)
      : service_(service), live_(std::move(live)), deadline_(deadline) {}

  void report(const ProgressInfo& info) override {
    std::lock_guard lock(service_.mutex_);
    live_->progress = info;
    ++service_.version_;
    service_.change_cv_.notify_all();
  }
  void intermediate(JobOutput output) override {
    auto shared = std::make_shared<const JobOutput>(std::move(output));
    std::lock_guard lock(service_.mutex_);
    live_->intermediate = std::move(shared);
    ++service_.version_;
    service_.change_cv_.notify_all();
  }
  bool cancelled() override {
    if (live_->cancel || service_.abort_running_) return true;
    if (now_seconds() > deadline_) timed_out_ = true;
    return timed_out_;
  }
  bool timed_out() const { return timed_out_; }

 private:
  JobService& service_;
  std::shared_ptr<Live> live_;
  double deadline_;
  bool timed_out_ = false;
};

namespace {

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f s", seconds);
  return text;
}

std::uint64_t fnv1a(std::uint64_t h, std::string_view bytes) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
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
  feed(options_to_json(options).dump());
  char text[33];
  std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(a),
                static_cast<unsigned long long>(b));
  return text;
}

JobService::JobService(JobStore& store, JobRunner runner, ServiceSettings settings, Logger log)
    : store_(store),
      runner_(std::move(runner)),
      settings_(settings),
      log_(std::move(log)),
      buckets_{0.1, 0.5, 1, 2, 5, 10, 30, 60, 120, 300, 600},
      bucket_counts_(buckets_.size() + 1, 0) {}

JobService::~JobService() { shutdown(std::chrono::milliseconds(0)); }

void JobService::start() {
  {
    std::lock_guard lock(mutex_);
    for (const JobRecord& job : store_.unfinished()) {
      if (job.status == JobStatus::Running) store_.requeue(job.id);
      queue_.push_back(job.id);
      live_[job.id] = std::make_shared<Live>();
      log_("job " + job.id + " " + status_name(job.status) + " -> queued (recovered)");
    }
  }
  for (std::size_t i = 0; i < settings_.workers; ++i) workers_.emplace_back([this] { work(); });
}

JobRecord JobService::submit(JobInput input, JobOptions options) {
  if (!accepting_) throw ApiError("shutting_down", "the server is shutting down; try again");
  if (!options.time_limit) options.time_limit = settings_.default_time_limit;
  JobRecord job;
  job.id = new_job_id();
  job.created = now_seconds();
  job.options = options_to_json(options);
  job.format = format_name(input.format);
  job.input_bytes = input.mesh.size();
  for (const auto& [name, data] : input.external_files) job.input_bytes += data.size();
  job.input_key = job_input_key(input, options);

  if (settings_.reuse_results) {
    if (auto prior = store_.find_reusable(job.input_key, input)) {
      job.status = prior->status;
      job.started = job.finished = job.created;
      job.input_faces = prior->input_faces;
      job.faces = prior->faces;
      job.overlaps = prior->overlaps;
      job.result_kind = prior->result_kind;
      job.metrics = prior->metrics;
      job.metrics["reused_from"] = prior->id;
      job.result_job = prior->result_job;
      store_.insert(job, nullptr);
      log_("job " + job.id + " -> " + status_name(job.status) + " (reused " + prior->id + ")");
      return job;
    }
  }
  {
    std::lock_guard lock(mutex_);
    if (queue_.size() + reserved_ >= settings_.queue_length) {
      Problem p = make_problem("queue_full", "the job queue is full (" +
                                                 std::to_string(settings_.queue_length) +
                                                 " jobs); retry later");
      p.retry_after = static_cast<int>(retry_after_seconds());
      throw ApiError(p);
    }
    ++reserved_;
  }
  try {
    store_.insert(job, &input);
  } catch (...) {
    std::lock_guard lock(mutex_);
    --reserved_;
    throw;
  }
  log_("job " + job.id + " -> queued (" + job.format + ", " + std::to_string(job.input_bytes) +
       " bytes)");
  {
    std::lock_guard lock(mutex_);
    --reserved_;
    queue_.push_back(job.id);
    live_[job.id] = std::make_shared<Live>();
    ++version_;
  }
  work_cv_.notify_one();
  change_cv_.notify_all();
  return job;
}

std::optional<JobView> JobService::view(const std::string& id) {
  std::optional<JobRecord> record = store_.find(id);
  if (!record) return std::nullopt;
  JobView view{std::move(*record), std::nullopt, 0, false, nullptr, {}};
  if (is_final(view.record.status)) {
    if (!view.record.result_job.empty())
      view.result_files = store_.artifact_names(view.record.result_job);
    return view;
  }
  std::lock_guard lock(mutex_);
  auto it = live_.find(id);
  if (it == live_.end()) return view;
  view.record.status = it->second->status;
  view.progress = it->second->progress;
  view.cancel_requested = it->second->cancel;
  view.intermediate = it->second->intermediate;
  if (it->second->status == JobStatus::Queued) {
    auto pos = std::find(queue_.begin(), queue_.end(), id);
    if (pos != queue_.end())
      view.queue_position = static_cast<std::size_t>(pos - queue_.begin()) + 1;
  }
  return view;
}

JobView JobService::cancel(const std::string& id) {
  std::optional<JobRecord> record = store_.find(id);
  if (!record) throw ApiError("job_not_found", "no job " + id);
  if (is_final(record->status)) {
    if (record->status == JobStatus::Cancelled) return *view(id);
    throw ApiError("job_finished", "job " + id + " already " + status_name(record->status));
  }
  bool dequeued = false;
  {
    std::lock_guard lock(mutex_);
    auto it = live_.find(id);
    if (it != live_.end()) {
      it->second->cancel = true;
      auto pos = std::find(queue_.begin(), queue_.end(), id);
      if (pos != queue_.end()) {
        queue_.erase(pos);
        live_.erase(it);
        dequeued = true;
      }
      ++version_;
    }
  }
  if (dequeued) {
    record->finished = now_seconds();
    finish(*record, JobStatus::Cancelled, nullptr,
           problem_json(make_problem("job_cancelled", "cancelled while queued")));
  }
  change_cv_.notify_all();
  return *view(id);
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
    auto running = [&] {
      return std::any_of(live_.begin(), live_.end(),
                         [](const auto& e) { return e.second->status == JobStatus::Running; });
    };
    if (running()) log_("shutdown: waiting for running jobs");
    change_cv_.wait_for(lock, grace, [&] { return !running(); });
    abort_running_ = true;
    stop_ = true;
  }
  work_cv_.notify_all();
  change_cv_.notify_all();
  for (std::thread& t : workers_)
    if (t.joinable()) t.join();
  workers_.clear();
}

ServiceStats JobService::stats() {
  ServiceStats s;
  s.jobs_by_status = store_.count_by_status();
  std::lock_guard lock(mutex_);
  s.queued = queue_.size();
  for (const auto& [id, live] : live_)
    if (live->status == JobStatus::Running) ++s.running;
  s.duration_buckets = buckets_;
  s.duration_counts = bucket_counts_;
  s.duration_sum = duration_sum_;
  s.duration_count = duration_count_;
  return s;
}

std::size_t JobService::retry_after_seconds() const {
  const double mean = duration_count_ ? duration_sum_ / static_cast<double>(duration_count_) : 5;
  const double wait = mean * static_cast<double>(queue_.size()) /
                      static_cast<double>(std::max<std::size_t>(1, settings_.workers));
  return static_cast<std::size_t>(std::clamp(std::ceil(wait), 1.0, 600.0));
}

void JobService::work() {
  for (;;) {
    std::string id;
    {
      std::unique_lock lock(mutex_);
      work_cv_.wait(lock, [&] { return stop_ || (!draining_ && !queue_.empty()); });
      if (stop_ || draining_) return;
      id = queue_.front();
      queue_.pop_front();
      live_[id]->status = JobStatus::Running;
      ++version_;
    }
    change_cv_.notify_all();
    try {
      run_one(id);
    } catch (const std::exception& e) {
      // Only the store can throw here (disk full, corrupt file): the job stays unfinished in
      // the store and runs again after a restart.
      log_("job " + id + " store error: " + e.what());
      std::lock_guard lock(mutex_);
      live_.erase(id);
      ++version_;
    }
    change_cv_.notify_all();
  }
}

void JobService::run_one(const std::string& id) {
  const double started = now_seconds();
  store_.mark_running(id, started);
  JobRecord record = *store_.find(id);
  log_("job " + id + " queued -> running (attempt " + std::to_string(record.attempts) + ")");
  std::shared_ptr<Live> live;
  {
    std::lock_guard lock(mutex_);
    live = live_[id];
  }
  if (record.attempts > settings_.max_attempts) {
    record.finished = now_seconds();
    finish(
        record, JobStatus::Failed, nullptr,
        problem_json(make_problem("interrupted_too_often",
                                  "the job was interrupted " + std::to_string(record.attempts - 1) +
                                      " times (server stopped or crashed while running it)")));
    return;
  }
  JobOptions options;
  JobInput input;
  try {
    options = parse_options_json(record.options.dump(), settings_.options_limits);
    input = store_.input(id);
  } catch (...) {
    record.finished = now_seconds();
    finish(record, JobStatus::Failed, nullptr,
           problem_json(problem_from_exception(std::current_exception())));
    return;
  }
  const double limit = options.time_limit.value_or(settings_.default_time_limit);
  Sink sink(*this, live, started + limit + settings_.hard_time_grace);
  try {
    JobOutput output = runner_(input, options, sink);
    record.finished = now_seconds();
    record.input_faces = output.input_faces;
    record.faces = output.faces;
    record.overlaps = output.overlaps;
    record.metrics = output.metrics;
    record.result_kind = output.approximate ? "approximate" : "complete";
    record.result_job = record.id;
    finish(record, output.approximate ? JobStatus::Approximated : JobStatus::Succeeded, &output,
           nullptr);
  } catch (...) {
    record.finished = now_seconds();
    {
      std::lock_guard lock(mutex_);
      if (live->progress) record.input_faces = live->progress->input_faces;
    }
    if (abort_running_ && !live->cancel) {
      store_.requeue(id);
      log_("job " + id + " running -> queued (server stopping)");
      std::lock_guard lock(mutex_);
      live_.erase(id);
      ++version_;
      return;
    }
    if (live->cancel) {
      finish(record, JobStatus::Cancelled, nullptr,
             problem_json(make_problem("job_cancelled", "cancelled while running")));
    } else if (sink.timed_out()) {
      finish(record, JobStatus::Failed, nullptr,
             problem_json(make_problem("time_limit_exceeded",
                                       "the job did not finish within its time limit of " +
                                           std::to_string(limit) + " seconds")));
    } else {
      finish(record, JobStatus::Failed, nullptr,
             problem_json(problem_from_exception(std::current_exception())));
    }
  }
}

void JobService::finish(JobRecord& record, JobStatus status, const JobOutput* output,
                        const nlohmann::json& error) {
  const JobStatus before = record.status;
  record.status = status;
  record.error = error;
  store_.finish(record, output);
  const double seconds = record.started > 0 ? record.finished - record.started : 0;
  {
    std::lock_guard lock(mutex_);
    live_.erase(record.id);
    ++version_;
    if (record.started > 0) {
      for (std::size_t i = 0; i < buckets_.size(); ++i)
        if (seconds <= buckets_[i]) ++bucket_counts_[i];
      ++bucket_counts_.back();
      duration_sum_ += seconds;
      ++duration_count_;
    }
  }
  change_cv_.notify_all();
  std::string line = "job " + record.id + " " + status_name(before) + " -> " + status_name(status);
  if (record.started > 0) line += " after " + seconds_text(seconds);
  if (error.is_object())
    line += " (" + error.value("code", "") + ": " + error.value("detail", "") + ")";
  log_(line);
}

}  // namespace papernet::server
