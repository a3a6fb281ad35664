// What the job service (job_service.h) takes and gives: its settings, who submits a job, a job
// as a client sees it, and the counters it reports for /metrics.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "api/options.h"
#include "core/progress.h"
#include "server/job.h"
#include "server/store_records.h"

namespace papernet::server {

/// The service's limits (a slice of ServerConfig).
struct ServiceSettings {
  std::size_t workers = 1;
  std::size_t queue_length = 64;  ///< queued jobs in the store (of every node) before 429
  OptionsLimits options_limits;
  double default_time_limit = 120;
  /// A job that overruns its time_limit by this much (the unfolder should stop by itself) is
  /// cancelled and fails with time_limit_exceeded.
  double hard_time_grace = 5;
  bool reuse_results = true;
  int max_attempts = 3;       ///< a job claimed again this often (its node died each time) fails
  double lease_seconds = 30;  ///< a running job's lease; renewed five times a second
  std::string node;           ///< this node's name in the store ("" = host, pid and a random tag)
  /// Seconds a finished job is kept before JobStore::expire removes its files (0 = forever);
  /// swept every retention/2 seconds, at most every minute.
  double retention_seconds = 7 * 86400;
  /// Bytes of files the store keeps at most (0 = no bound): the sweep expires the finished jobs
  /// that finished first until the store holds no more (JobStore::stored_bytes); swept every
  /// 2 seconds then.
  std::uint64_t max_store_bytes = 0;
};

/// Who submits a job, and on what terms.
struct Submitter {
  std::string tenant;      ///< the API key's tenant ("" without keys)
  std::string job_id;      ///< the new job's id ("" = a new random one)
  double queue_share = 1;  ///< the most of the queue this tenant's queued jobs may fill
};

/// A job as a client sees it: the stored record plus, while it is queued or running, the live
/// state (progress, queue position, latest overlap-free intermediate), from this node's memory
/// when it runs here and from what its node published to the store otherwise.
struct JobView {
  JobRecord record;
  std::optional<ProgressInfo> progress;
  std::size_t queue_position = 0;  ///< 1 = next; 0 = not queued
  bool cancel_requested = false;
  std::optional<IntermediateLevel> intermediate;
  std::vector<std::string> result_files;    ///< stored result files of a finished job
  std::optional<WebhookDelivery> callback;  ///< its callback's delivery, with a callback_url
};

/// Counters for /metrics.
struct ServiceStats {
  std::size_t queued = 0;   ///< in the store: every node's queue
  std::size_t running = 0;  ///< on this node
  std::map<std::string, std::size_t> jobs_by_status;
  std::map<std::string, std::size_t> queued_by_tenant;  ///< in the store, by tenant
  std::vector<double> duration_buckets;                 ///< upper bounds in seconds
  std::vector<std::uint64_t> duration_counts;           ///< cumulative, one per bucket, then +Inf
  double duration_sum = 0;
  std::uint64_t duration_count = 0;
  std::string store_kind;
  bool store_up = true;
  std::uint64_t claims = 0;          ///< jobs this node's workers claimed
  std::uint64_t lease_expiries = 0;  ///< of those, taken over from a node whose lease ran out
  std::uint64_t leases_lost = 0;     ///< jobs this node ran whose lease passed to another node
  std::uint64_t stored_bytes = 0;    ///< JobStore::stored_bytes (every node's jobs)
  StoreStats store;
};

}  // namespace papernet::server
