#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "server/job.h"

struct sqlite3;

namespace papernet::server {

/// Durable home of jobs, their inputs and their results: one SQLite database in WAL mode.
/// Every write is one transaction, so a kill -9 leaves either the old or the new state.
/// Thread-safe (one connection behind a mutex).
class JobStore {
 public:
  /// Opens or creates `path` (":memory:" for tests).
  /// \throw std::runtime_error when the database cannot be opened or migrated.
  explicit JobStore(const std::string& path);
  ~JobStore();
  JobStore(const JobStore&) = delete;
  JobStore& operator=(const JobStore&) = delete;

  /// Stores a new job with its input (when `input` is set) atomically. Fills `job.seq`.
  void insert(JobRecord& job, const JobInput* input);
  std::optional<JobRecord> find(const std::string& id);
  /// Most recent first; `before_seq` > 0 pages on (jobs with a smaller seq).
  std::vector<JobRecord> list(std::size_t limit, std::int64_t before_seq = 0);
  /// Queued and running jobs, oldest first: what a restart must run again.
  std::vector<JobRecord> unfinished();
  /// \throw std::runtime_error when the job has no stored input.
  JobInput input(const std::string& id);

  /// Marks the job running and counts the attempt.
  void mark_running(const std::string& id, double started);
  /// Puts a running job back in the queue (shutdown interrupted it).
  void requeue(const std::string& id);
  /// Stores the final state; for succeeded/approximated also `output`'s files, atomically.
  void finish(const JobRecord& job, const JobOutput* output);

  /// A file of a finished job's result.
  std::optional<Artifact> artifact(const std::string& result_job, const std::string& name);
  /// Names of the stored result files of `result_job`.
  std::vector<std::string> artifact_names(const std::string& result_job);
  /// A finished, successful job with exactly this input and key (for result reuse).
  std::optional<JobRecord> find_reusable(const std::string& input_key, const JobInput& input);
  /// Jobs per status name.
  std::map<std::string, std::size_t> count_by_status();

 private:
  std::mutex mutex_;
  sqlite3* db_ = nullptr;
};

}  // namespace papernet::server
