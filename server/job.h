#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "api/options.h"
#include "core/io/load.h"
#include "core/progress.h"
#include "engine/pipeline.h"

namespace papernet::server {

enum class JobStatus { Queued, Running, Succeeded, Approximated, Failed, Cancelled };

std::string status_name(JobStatus status);
/// \throw std::invalid_argument for a name that is no status.
JobStatus parse_status(const std::string& name);
/// True for succeeded, approximated, failed and cancelled: nothing will change any more.
bool is_final(JobStatus status);

/// One downloadable file of a result ("net.json", "net.svg", "net.pdf", "mesh.glb").
struct Artifact {
  std::string content_type;
  std::string data;
};

/// What a run produced, final or intermediate.
struct JobOutput {
  bool approximate = false;  ///< the net folds into a coarser mesh than the input
  std::size_t input_faces = 0;
  std::size_t faces = 0;  ///< faces of the mesh the net folds into
  std::size_t overlaps = 0;
  std::map<std::string, Artifact> files;
  /// The result's metrics, and under "repairs" and "pieces" what the net JSON lists by those
  /// names: stored together, shown apart (job_json).
  nlohmann::json metrics = nlohmann::json::object();
};

/// What the service offers a running job: progress in, intermediates in, cancellation out.
class JobSink {
 public:
  virtual ~JobSink() = default;
  virtual void report(const ProgressInfo& info) = 0;
  /// The latest overlap-free intermediate result (replaces the previous one).
  virtual void intermediate(JobOutput output) = 0;
  /// True once the job was cancelled, timed out or the server is stopping.
  virtual bool cancelled() = 0;
};

/// Runs one job on a worker thread: geometry happens here and nowhere else. `options` has its
/// time_limit filled in. Throws on failure (the service maps the exception to a problem);
/// throws CancelledException when the sink said stop.
using JobRunner =
    std::function<JobOutput(const JobInput& input, const JobOptions& options, JobSink& sink)>;

/// A job as the store keeps it. Times are seconds since the Unix epoch (0 = not yet).
struct JobRecord {
  std::string id;
  std::string tenant;    ///< the API key's tenant that submitted it ("" without keys)
  std::int64_t seq = 0;  ///< submission order
  JobStatus status = JobStatus::Queued;
  double created = 0;
  double started = 0;
  double finished = 0;
  nlohmann::json options = nlohmann::json::object();
  std::string format;
  std::size_t input_bytes = 0;
  std::string input_key;  ///< hash of mesh + files + options, for result reuse
  std::size_t input_faces = 0;
  std::size_t faces = 0;
  std::size_t overlaps = 0;
  std::string result_kind;  ///< "complete" or "approximate" once finished with a result
  nlohmann::json metrics = nlohmann::json::object();
  nlohmann::json error;    ///< the problem document of a failed job, null otherwise
  std::string result_job;  ///< job whose stored files are this job's result (itself or reused)
  int attempts = 0;        ///< times a worker claimed it (a crash or an expired lease adds one)
  std::string node;        ///< the node whose worker claimed it last ("" while never claimed)
  bool cancel_requested = false;  ///< a client asked a running job to stop
  nlohmann::json progress;        ///< a running job's last published progress, or null
  nlohmann::json intermediate;    ///< a running job's published intermediate (level), or null
  std::vector<std::string> result_files;  ///< names of the stored files of `result_job`
  bool expired = false;  ///< past retention: its input and files are gone, the id answers 410
};

/// A running job's latest overlap-free intermediate as a client sees it: its level and files.
struct IntermediateLevel {
  std::size_t faces = 0;
  std::size_t input_faces = 0;
  std::size_t overlaps = 0;
  std::vector<std::string> files;
};

/// One file of an intermediate, with the level it belongs to.
struct IntermediateFile {
  Artifact file;
  std::size_t faces = 0;
  std::size_t input_faces = 0;
};

/// The format a record names (JobRecord::format, format_name's words).
MeshFormat format_of_record(const std::string& name);

/// The file names a store lists in one column ("mesh.glb/net.json"), sorted.
std::vector<std::string> split_file_names(const std::string& joined);

/// How the store keeps a running job's progress and intermediate level for other nodes.
nlohmann::json progress_to_json(const ProgressInfo& info);
/// nullopt for null (nothing published) or a document that is not a progress.
std::optional<ProgressInfo> progress_from_json(const nlohmann::json& doc);
nlohmann::json intermediate_level_json(const JobOutput& output);
std::optional<IntermediateLevel> intermediate_level_from_json(const nlohmann::json& doc);

/// Opaque job ids: 32 lowercase hex digits from a random source.
std::string new_job_id();
/// True when `id` has the shape new_job_id() produces; anything else is never looked up.
bool valid_job_id(std::string_view id);

/// Seconds since the Unix epoch, now.
double now_seconds();

}  // namespace papernet::server
