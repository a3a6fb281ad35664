// The job service: the workers that run jobs from the store's queue, and what the HTTP threads
// ask of it. The settings it takes and the views and counters it gives: service_records.h.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "server/job.h"
#include "server/job_store.h"
#include "server/service_records.h"
#include "server/store_records.h"

namespace papernet::server {

/// Runs jobs from the store's queue on a fixed pool of worker threads, keeping every state
/// change in the store, so that with a shared store any node answers for any job. Callers
/// (HTTP threads) only submit, look and cancel.
class JobService {
 public:
  using Logger = std::function<void(const std::string&)>;
  JobService(JobStore& store, JobRunner runner, ServiceSettings settings, Logger log);
  ~JobService();
  JobService(const JobService&) = delete;
  JobService& operator=(const JobService&) = delete;

  /// Makes claimable what a stopped process left running (JobStore::recover_interrupted),
  /// listens to other nodes and starts the workers and the lease keeper. Call once.
  void start();

  /// Stores the job and queues it, or answers it from an identical finished job.
  /// \throw ApiError queue_full (with Retry-After) or shutting_down; StoreError.
  /// The job belongs to `by.tenant`; only that tenant's results are reused. A tenant whose
  /// queued jobs fill its `queue_share` of the queue (at least one job) is refused as a full
  /// queue is.
  JobRecord submit(JobInput input, JobOptions options, const Submitter& by = {});
  /// JobStore::remember_idempotency and forget_idempotency (Idempotency-Key).
  IdempotencyRecord remember_idempotency(const std::string& tenant, const std::string& key,
                                         const IdempotencyRecord& record, double since) {
    return store_.remember_idempotency(tenant, key, record, since);
  }
  void forget_idempotency(const std::string& tenant, const std::string& key,
                          const std::string& job_id) {
    store_.forget_idempotency(tenant, key, job_id);
  }

  /// With `tenant`, another tenant's job is nullopt as soon as its record is read, so that it
  /// costs what a missing one does (no queue position or live state is looked up).
  std::optional<JobView> view(const std::string& id, const std::string* tenant = nullptr);
  /// `tenant`'s jobs, most recent first; `before_seq` > 0 pages on.
  std::vector<JobRecord> list(const std::string& tenant, std::size_t limit,
                              std::int64_t before_seq) {
    return store_.list(tenant, limit, before_seq);
  }
  /// A stored result file (of a finished job's `result_job`).
  std::optional<Artifact> artifact(const std::string& result_job, const std::string& name) {
    return store_.artifact(result_job, name);
  }
  /// A file of a running job's latest intermediate, wherever it runs.
  std::optional<IntermediateFile> intermediate(const std::string& id, const std::string& name);
  /// Cancels a queued job at once and asks a running one to stop (its node stops it at the
  /// job's next progress poll, within a second). \throw ApiError job_not_found, or job_finished
  /// for a job that had ended (cancelled included) before this call.
  JobView cancel(const std::string& id);

  /// Blocks until something changed after `seen` (or `timeout`); returns the new version.
  std::uint64_t wait_for_change(std::uint64_t seen, std::chrono::milliseconds timeout);
  std::uint64_t version();

  /// Stops accepting and starting jobs, gives running jobs `grace` to finish, then stops them
  /// and puts them back in the queue. Idempotent.
  void shutdown(std::chrono::milliseconds grace);
  bool accepting() const { return accepting_; }
  /// \throw StoreUnavailable when the store cannot be reached (/readyz).
  void check_store() { store_.ping(); }
  const std::string& node() const { return settings_.node; }
  ServiceStats stats();

 private:
  struct Live;
  class Sink;
  void work();
  void run_one(ClaimedJob claimed);
  void keep_leases();
  void sweep(std::chrono::steady_clock::time_point& next);
  void on_store_event(const StoreEvent& event);
  bool finish(JobRecord& record, const Claim& claim, JobStatus status, const JobOutput* output,
              const nlohmann::json& error);
  void forget(const std::string& id);
  std::size_t retry_after_seconds(std::size_t queued);

  JobStore& store_;
  JobRunner runner_;
  ServiceSettings settings_;
  Logger log_;

  std::mutex mutex_;
  std::condition_variable work_cv_;
  std::condition_variable change_cv_;
  std::condition_variable keeper_cv_;
  std::uint64_t wakeups_ = 0;  // submissions and other nodes' "queued": a claim may succeed
  std::map<std::string, std::shared_ptr<Live>> live_;  // jobs running on this node
  std::uint64_t version_ = 0;
  std::atomic<bool> accepting_{true};
  bool draining_ = false;  // no new job starts
  bool stop_ = false;      // workers exit
  bool keeper_stop_ = false;
  std::atomic<bool> abort_running_{false};
  std::vector<std::thread> workers_;
  std::thread keeper_;
  std::vector<double> buckets_;
  std::vector<std::uint64_t> bucket_counts_;
  double duration_sum_ = 0;
  std::uint64_t duration_count_ = 0;
  std::uint64_t claims_ = 0, lease_expiries_ = 0, leases_lost_ = 0;
};

/// Hash of mesh bytes, external files and canonical options: equal inputs, equal keys.
std::string job_input_key(const JobInput& input, const JobOptions& options);

}  // namespace papernet::server
