#include "server/pipeline_runner.h"

#include "core/errors.h"
#include "core/load.h"
#include "core/validate.h"
#include "server/problem.h"

namespace papernet::server {
namespace {

// Loads and validates; what cannot be unfolded fails here with the validator's reasons (422).
Mesh load_and_validate(const JobInput& input, const JobOptions& options,
                       const PipelineLimits& limits, JobSink& sink) {
  LoadOptions load_options;
  load_options.max_bytes = limits.max_bytes;
  // Above the limit, so that "too many faces" is ours to say (413) for all but absurd meshes.
  load_options.max_faces = limits.max_faces * 4 + 16;
  load_options.external_files = input.external_files;
  ProgressInfo info;
  info.phase = "load";
  sink.report(info);
  LoadedMesh loaded = load_mesh(input.mesh, input.format, load_options);
  info.input_faces = loaded.mesh.faces.size();
  info.faces = info.input_faces;
  info.phase = "validate";
  sink.report(info);
  if (loaded.mesh.faces.size() > limits.max_faces)
    throw ApiError("too_many_faces", "the mesh has " + std::to_string(loaded.mesh.faces.size()) +
                                         " faces; this server unfolds at most " +
                                         std::to_string(limits.max_faces));
  ValidateOptions validate_options;
  validate_options.keep_largest_component = options.keep_largest_component;
  ValidationReport report = validate(loaded, validate_options);
  if (!report.unfoldable()) {
    nlohmann::json reasons = nlohmann::json::array();
    for (const papernet::Problem& p : report.problems)
      if (p.blocking)
        reasons.push_back({{"code", p.code}, {"message", p.message}, {"elements", p.elements}});
    throw ApiError("invalid_mesh", report.reason(),
                   {{"reasons", reasons},
                    {"mesh",
                     {{"vertices", report.vertices},
                      {"faces", report.faces},
                      {"components", report.components},
                      {"genus", report.genus},
                      {"boundary_loops", report.boundary_loops}}}});
  }
  if (sink.cancelled()) throw CancelledException();
  if (options.keep_largest_component && !report.largest_component.faces.empty())
    return std::move(report.largest_component);
  return std::move(loaded.mesh);
}

}  // namespace

JobRunner make_pipeline_runner(PipelineLimits limits) {
  return [limits](const JobInput& input, const JobOptions& options, JobSink& sink) -> JobOutput {
    const Mesh mesh = load_and_validate(input, options, limits, sink);
    throw ApiError("pipeline_unavailable",
                   "this build can load and validate the mesh (" +
                       std::to_string(mesh.faces.size()) + " faces) but has no unfolder yet");
  };
}

}  // namespace papernet::server
