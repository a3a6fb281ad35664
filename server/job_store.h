// The job store's interface, which the SQLite and PostgreSQL stores implement, and the function
// that opens the one a spec names. The errors and records it speaks in: store_records.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "server/job.h"
#include "server/store_records.h"

namespace papernet::server {

/// Durable home of jobs, their inputs, progress, results and the queue (DESIGN "Stores",
/// docs/scaling.md): the embedded SQLite file for one node, or PostgreSQL shared by several.
/// Every write is one transaction; all methods are thread-safe and throw StoreError (or
/// StoreUnavailable) when the store fails.
class JobStore {
 public:
  virtual ~JobStore() = default;
  /// "sqlite" or "postgres".
  virtual std::string kind() const = 0;

  /// Stores a new job with its input (when `input` is set) atomically and fills `job.seq`,
  /// unless `queue_limit` jobs are queued already: then stores nothing and returns false.
  virtual bool insert(JobRecord& job, const JobInput* input, std::size_t queue_limit) = 0;
  virtual std::optional<JobRecord> find(const std::string& id) = 0;
  /// `tenant`'s jobs, most recent first; `before_seq` > 0 pages on (jobs with a smaller seq).
  virtual std::vector<JobRecord> list(const std::string& tenant, std::size_t limit,
                                      std::int64_t before_seq) = 0;
  /// \throw StoreError when the job has no stored input.
  virtual JobInput input(const std::string& id) = 0;
  /// A finished, successful job of `tenant` with exactly this input and key (for result
  /// reuse, which never crosses tenants).
  virtual std::optional<JobRecord> find_reusable(const std::string& tenant,
                                                 const std::string& input_key,
                                                 const JobInput& input) = 0;
  /// Records that `tenant`'s `key` stands for `record`, unless the key already stands for a
  /// record created at `since` or later: returns the record the key stands for now (`record`,
  /// or the earlier one). Atomic: of two requests with one key, one wins.
  virtual IdempotencyRecord remember_idempotency(const std::string& tenant, const std::string& key,
                                                 const IdempotencyRecord& record, double since) = 0;
  /// Drops the key's record when it names `job_id` (its job could not be stored).
  virtual void forget_idempotency(const std::string& tenant, const std::string& key,
                                  const std::string& job_id) = 0;
  /// Retention: every finished job that finished before `finished_before` becomes expired (its
  /// row stays, small, so its id answers 410): its input, intermediates and result files are
  /// removed (a result other jobs still reuse stays until they expire too). Idempotency-Key
  /// records created before `keys_before` go. Returns the jobs that expired now.
  virtual std::size_t expire(double finished_before, double keys_before) = 0;
  /// The bytes of every upload, intermediate and result file held (their lengths as stored,
  /// before the database's own compression): what retention and the size bound remove.
  virtual std::uint64_t stored_bytes() = 0;
  /// When the finished job that finished first and has not expired finished (nullopt: none).
  virtual std::optional<double> oldest_finished() = 0;
  /// `tenant`'s queued jobs.
  virtual std::size_t queued_count(const std::string& tenant) = 0;
  /// Queued jobs per tenant (tenants with none left out), for /metrics.
  virtual std::map<std::string, std::size_t> queued_by_tenant() = 0;
  /// Jobs per status name.
  virtual std::map<std::string, std::size_t> count_by_status() = 0;
  /// 1 for the next queued job to run, 2 for the one after, ...
  virtual std::size_t queue_position(std::int64_t seq) = 0;

  /// At start: makes claimable again what a process that is gone left running. The SQLite
  /// store (one node) requeues every running job and returns their ids; PostgreSQL leaves
  /// that to lease expiry and returns nothing.
  virtual std::vector<std::string> recover_interrupted() = 0;
  /// Claims the oldest queued job, or the oldest running one whose lease has expired, for
  /// `node`: marks it running under a lease of `lease_seconds` and counts the attempt.
  virtual std::optional<ClaimedJob> claim(const std::string& node, double lease_seconds,
                                          double started) = 0;
  /// Extends the lease; with `progress` also publishes the job's progress to other nodes.
  virtual LeaseState renew(const std::string& id, const Claim& claim, double lease_seconds,
                           const nlohmann::json* progress) = 0;
  /// Publishes a running job's latest overlap-free intermediate; false when not held.
  virtual bool put_intermediate(const std::string& id, const Claim& claim,
                                const JobOutput& output) = 0;
  /// A file of a running job's published intermediate.
  virtual std::optional<IntermediateFile> intermediate(const std::string& id,
                                                       const std::string& name) = 0;
  /// Stores a running job's final state (`job.status`, `job.error`, ...) and, for
  /// succeeded/approximated, `output`'s files atomically. False when `claim` no longer holds it.
  virtual bool finish(const JobRecord& job, const Claim& claim, const JobOutput* output) = 0;
  /// Puts a running job back in the queue (its node is stopping); false when not held.
  virtual bool release(const std::string& id, const Claim& claim) = 0;
  /// Cancels a queued job (storing `error` and `finished`) or asks a running one to stop.
  virtual CancelOutcome cancel(const std::string& id, const nlohmann::json& error,
                               double finished) = 0;

  /// A file of a finished job's result.
  virtual std::optional<Artifact> artifact(const std::string& result_job,
                                           const std::string& name) = 0;

  /// The callback delivery of job `id`, if it named a callback_url.
  virtual std::optional<WebhookDelivery> webhook(const std::string& id) = 0;
  /// Claims, for `node`, the pending delivery of a finished job that is due at `now` and no
  /// other node holds: it is this node's to attempt for `lease_seconds`.
  virtual std::optional<WebhookDelivery> claim_webhook(const std::string& node, double now,
                                                       double lease_seconds) = 0;
  /// Stores an attempt's outcome (state, attempts, next_at) and ends `node`'s claim; false when
  /// the claim passed to another node meanwhile (nothing is stored then).
  virtual bool update_webhook(const WebhookDelivery& delivery, const std::string& node) = 0;

  /// Calls `on_event` (from a thread of the store's own) for what other nodes do; an empty
  /// function stops that. A store with one node (SQLite) has nothing to tell and never calls.
  virtual void listen(std::function<void(const StoreEvent&)> on_event) { (void)on_event; }
  /// \throw StoreUnavailable when the store cannot be reached now (/readyz).
  virtual void ping() = 0;
  virtual StoreStats stats() { return {}; }
};

/// Opens the store `spec` names: "sqlite" (the file papernet.sqlite under `data_dir`) or a
/// postgres:// URL with a pool of `connections`. Applies the schema's migrations.
/// \throw StoreError with a message fit for the operator (a URL's password left out).
std::unique_ptr<JobStore> open_job_store(const std::string& spec, const std::string& data_dir,
                                         std::size_t connections);

/// True for a postgres:// or postgresql:// URL.
bool is_postgres_url(const std::string& spec);

/// `url` with its password replaced by "***", for messages and logs.
std::string redact_store_url(const std::string& url);

}  // namespace papernet::server
