#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "server/job.h"
#include "server/job_store.h"

namespace papernet::server {

/// The service's limits (a slice of ServerConfig).
struct ServiceSettings {
  std::size_t workers = 1;
  std::size_t queue_length = 64;
  OptionsLimits options_limits;
  double default_time_limit = 120;
  /// A job that overruns its time_limit by this much (the unfolder should stop by itself) is
  /// cancelled and fails with time_limit_exceeded.
  double hard_time_grace = 5;
  bool reuse_results = true;
  int max_attempts = 3;  ///< a job that took the server down this often fails instead
};

/// A job as a client sees it: the stored record plus, while it is queued or running, the live
/// state (progress, queue position, latest overlap-free intermediate).
struct JobView {
  JobRecord record;
  std::optional<ProgressInfo> progress;
  std::size_t queue_position = 0;  ///< 1 = next; 0 = not queued
  bool cancel_requested = false;
  std::shared_ptr<const JobOutput> intermediate;
  std::vector<std::string> result_files;  ///< stored result files of a finished job
};

/// Counters for /metrics.
struct ServiceStats {
  std::size_t queued = 0;
  std::size_t running = 0;
  std::map<std::string, std::size_t> jobs_by_status;
  std::vector<double> duration_buckets;        ///< upper bounds in seconds
  std::vector<std::uint64_t> duration_counts;  ///< cumulative, one per bucket, then +Inf
  double duration_sum = 0;
  std::uint64_t duration_count = 0;
};

/// Accepts jobs into a bounded queue and runs them on a fixed pool of worker threads, keeping
/// every state change in the store. Callers (HTTP threads) only enqueue, look and cancel.
class JobService {
 public:
  using Logger = std::function<void(const std::string&)>;
  JobService(JobStore& store, JobRunner runner, ServiceSettings settings, Logger log);
  ~JobService();
  JobService(const JobService&) = delete;
  JobService& operator=(const JobService&) = delete;

  /// Re-queues what the store says is unfinished (a crash or stop interrupted it) and starts
  /// the workers. Call once.
  void start();

  /// Stores the job and queues it, or answers it from an identical finished job.
  /// \throw ApiError queue_full (with Retry-After) or shutting_down.
  JobRecord submit(JobInput input, JobOptions options);

  std::optional<JobView> view(const std::string& id);
  /// Most recent first; `before_seq` > 0 pages on.
  std::vector<JobRecord> list(std::size_t limit, std::int64_t before_seq) {
    return store_.list(limit, before_seq);
  }
  /// A stored result file (of a finished job's `result_job`).
  std::optional<Artifact> artifact(const std::string& result_job, const std::string& name) {
    return store_.artifact(result_job, name);
  }
  /// Cancels a queued job at once and asks a running one to stop (it stops at its next
  /// progress poll). \throw ApiError job_not_found or job_finished.
  JobView cancel(const std::string& id);

  /// Blocks until something changed after `seen` (or `timeout`); returns the new version.
  std::uint64_t wait_for_change(std::uint64_t seen, std::chrono::milliseconds timeout);
  std::uint64_t version();

  /// Stops accepting and starting jobs, gives running jobs `grace` to finish, then stops them
  /// and leaves them queued in the store for the next start. Idempotent.
  void shutdown(std::chrono::milliseconds grace);
  bool accepting() const { return accepting_; }
  ServiceStats stats();

 private:
  struct Live;
  class Sink;
  void work();
  void run_one(const std::string& id);
  void finish(JobRecord& record, JobStatus status, const JobOutput* output,
              const nlohmann::json& error);
  std::size_t retry_after_seconds() const;

  JobStore& store_;
  JobRunner runner_;
  ServiceSettings settings_;
  Logger log_;

  std::mutex mutex_;
  std::condition_variable work_cv_;
  std::condition_variable change_cv_;
  std::deque<std::string> queue_;
  std::size_t reserved_ = 0;  // submissions between the capacity check and the queue
  std::map<std::string, std::shared_ptr<Live>> live_;
  std::uint64_t version_ = 0;
  std::atomic<bool> accepting_{true};
  bool draining_ = false;  // no new job starts
  bool stop_ = false;      // workers exit
  std::atomic<bool> abort_running_{false};
  std::vector<std::thread> workers_;
  std::vector<double> buckets_;
  std::vector<std::uint64_t> bucket_counts_;
  double duration_sum_ = 0;
  std::uint64_t duration_count_ = 0;
};

/// Hash of mesh bytes, external files and canonical options: equal inputs, equal keys.
std::string job_input_key(const JobInput& input, const JobOptions& options);

}  // namespace papernet::server
