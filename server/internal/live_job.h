// Private to the job service (job_service.cpp, job_workers.cpp): what this node knows of a job
// one of its workers runs.
#pragma once

#include <atomic>
#include <memory>
#include <optional>

#include "server/job_service.h"

namespace papernet::server {

struct JobService::Live {
  explicit Live(Claim c) : claim(std::move(c)) {}
  const Claim claim;
  // Guarded by the service's mutex: the latest progress and intermediate, and whether the lease
  // keeper has published them to the store yet.
  std::optional<ProgressInfo> progress;
  bool progress_published = true;
  std::shared_ptr<const JobOutput> intermediate;
  bool intermediate_published = true;
  std::atomic<bool> cancel{false};  // a client asked to stop it
  std::atomic<bool> lost{false};    // its lease passed to another node
};

}  // namespace papernet::server
