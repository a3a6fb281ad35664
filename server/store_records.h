// What the job store's interface (job_store.h) speaks in: the errors it throws, and the records
// it takes and returns about claims, leases, cancellations, other nodes' events, Idempotency-Keys,
// callback deliveries and its own counters.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "server/job.h"

namespace papernet::server {

/// A store operation failed: a full disk, a statement timeout, a corrupt file.
class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The store cannot be reached now (the database is down or restarting); a later try may work.
class StoreUnavailable : public StoreError {
 public:
  using StoreError::StoreError;
};

/// A worker's hold on a running job: the node and the attempt it claimed. Every write about a
/// running job names it, so a node whose lease passed to another cannot overwrite the job.
struct Claim {
  std::string node;
  int attempt = 0;
};

/// A job a worker just claimed. `expired_node` names the node whose lease ran out when the job
/// was taken over from it (docs/scaling.md), and is empty for a job that was queued.
struct ClaimedJob {
  JobRecord record;
  std::string expired_node;
};

/// What the holder of a running job learns when it renews its lease.
struct LeaseState {
  bool held = false;  ///< false: the lease passed to another node, or the job ended
  bool cancel_requested = false;
};

/// How a cancellation went in the store.
enum class CancelOutcome {
  Cancelled,  ///< the job was queued and is cancelled now
  Requested,  ///< the job runs; its node was told to stop it
  NotActive,  ///< the job is finished or does not exist
};

/// What other nodes told the store (PostgreSQL's LISTEN/NOTIFY): a job was queued, a job
/// changed (progress, result, state), or a running job is to be cancelled.
struct StoreEvent {
  enum class Kind { Queued, Changed, Cancel };
  Kind kind = Kind::Changed;
  std::string job_id;  ///< empty for Queued, and for Changed after a reconnect (anything changed)
};

/// What an Idempotency-Key stands for: the request it came with (a hash of the mesh, files and
/// options) and the job that request made.
struct IdempotencyRecord {
  std::string request_hash;
  std::string job_id;
  double created = 0;
};

/// A job's callback (webhook) delivery as the store keeps it (docs/security.md "Webhooks"):
/// made with the job when it names a callback_url, due once the job is final.
struct WebhookDelivery {
  std::string job_id;
  std::string url;
  std::string state = "pending";  ///< pending, delivered, or failed (gave up)
  /// Every attempt so far: {"at": seconds, "status": HTTP status} or {"at", "error": text}.
  nlohmann::json attempts = nlohmann::json::array();
  double next_at = 0;  ///< earliest time of the next attempt (seconds since the epoch)
};

/// The store's own counters for /metrics.
struct StoreStats {
  std::uint64_t reconnects = 0;  ///< connections to the database opened again after a loss
};

}  // namespace papernet::server
