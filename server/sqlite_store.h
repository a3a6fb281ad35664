#pragma once

#include <mutex>
#include <string>

#include "server/job_store.h"

struct sqlite3;

namespace papernet::server {

/// The embedded store of one node: one SQLite database in WAL mode, one connection behind a
/// mutex. Every write is one transaction, so a kill -9 leaves either the old or the new state.
/// Its schema is versioned (PRAGMA user_version) and migrated when the file is opened.
class SqliteJobStore : public JobStore {
 public:
  /// Opens or creates `path` (":memory:" for tests).
  /// \throw StoreError when the database cannot be opened or migrated.
  explicit SqliteJobStore(const std::string& path);
  ~SqliteJobStore() override;
  SqliteJobStore(const SqliteJobStore&) = delete;
  SqliteJobStore& operator=(const SqliteJobStore&) = delete;

  std::string kind() const override { return "sqlite"; }
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

  std::vector<std::string> recover_interrupted() override;
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

  // sqlite_webhooks.cpp
  std::optional<WebhookDelivery> webhook(const std::string& id) override;
  std::optional<WebhookDelivery> claim_webhook(const std::string& node, double now,
                                               double lease_seconds) override;
  bool update_webhook(const WebhookDelivery& delivery, const std::string& node) override;
  void ping() override {}

 private:
  std::mutex mutex_;
  sqlite3* db_ = nullptr;
};

}  // namespace papernet::server
