#pragma once

#include <memory>
#include <mutex>
#include <string>

#include "server/job_store.h"
#include "server/pg.h"

namespace papernet::server {

/// The store several nodes share (docs/scaling.md): jobs, inputs, progress, intermediates,
/// results and the queue in PostgreSQL. Workers claim the oldest claimable job with
/// `FOR UPDATE SKIP LOCKED` under a lease; changes are announced with NOTIFY on the channel
/// "papernet". The schema is versioned and migrated at start under an advisory lock, so nodes
/// starting together migrate it once.
class PgJobStore : public JobStore {
 public:
  /// Connects to `url` (a postgres:// URL) with a pool of `connections` and migrates.
  /// \throw StoreUnavailable when the database cannot be reached or refuses the login,
  /// StoreError when the schema cannot be migrated.
  PgJobStore(const std::string& url, std::size_t connections);
  ~PgJobStore() override;

  std::string kind() const override { return "postgres"; }
  bool insert(JobRecord& job, const JobInput* input, std::size_t queue_limit) override;
  std::optional<JobRecord> find(const std::string& id) override;
  std::vector<JobRecord> list(const std::string& tenant, std::size_t limit,
                              std::int64_t before_seq) override;
  JobInput input(const std::string& id) override;
  std::optional<JobRecord> find_reusable(const std::string& tenant, const std::string& input_key,
                                         const JobInput& input) override;
  IdempotencyRecord remember_idempotency(const std::string& tenant, const std::string& key,
                                         const IdempotencyRecord& record, double since) override;
  void forget_idempotency(const std::string& tenant, const std::string& key,
                          const std::string& job_id) override;
  std::size_t expire(double finished_before, double keys_before) override;
  std::uint64_t stored_bytes() override;
  std::optional<double> oldest_finished() override;
  std::size_t queued_count(const std::string& tenant) override;
  std::map<std::string, std::size_t> queued_by_tenant() override;
  std::map<std::string, std::size_t> count_by_status() override;
  std::size_t queue_position(std::int64_t seq) override;

  std::vector<std::string> recover_interrupted() override { return {}; }
  std::optional<ClaimedJob> claim(const std::string& node, double lease_seconds,
                                  double started) override;
  LeaseState renew(const std::string& id, const Claim& claim, double lease_seconds,
                   const nlohmann::json* progress) override;
  bool put_intermediate(const std::string& id, const Claim& claim,
                        const JobOutput& output) override;
  std::optional<IntermediateFile> intermediate(const std::string& id,
                                               const std::string& name) override;
  bool finish(const JobRecord& job, const Claim& claim, const JobOutput* output) override;
  bool release(const std::string& id, const Claim& claim) override;
  CancelOutcome cancel(const std::string& id, const nlohmann::json& error,
                       double finished) override;

  std::optional<Artifact> artifact(const std::string& result_job, const std::string& name) override;

  // pg_webhooks.cpp
  std::optional<WebhookDelivery> webhook(const std::string& id) override;
  std::optional<WebhookDelivery> claim_webhook(const std::string& node, double now,
                                               double lease_seconds) override;
  bool update_webhook(const WebhookDelivery& delivery, const std::string& node) override;

  void listen(std::function<void(const StoreEvent&)> on_event) override;
  void ping() override;
  StoreStats stats() override;

  /// The schema version this papernet migrates a database to.
  static int schema_version();

 private:
  void migrate();
  const std::string url_;
  pg::Pool pool_;
  std::mutex listener_mutex_;
  std::unique_ptr<pg::Listener> listener_;
};

}  // namespace papernet::server
