#include "server/pipeline_runner.h"

#include "core/errors.h"
#include "core/load.h"
#include "server/problem.h"

namespace papernet::server {

JobRunner make_pipeline_runner(PipelineLimits limits) {
  return [limits](const JobInput& input, const JobOptions&, JobSink& sink) -> JobOutput {
    LoadOptions load_options;
    load_options.max_bytes = limits.max_bytes;
    // Above the limit, so that "too many faces" is ours to say (413) for all but absurd meshes.
    load_options.max_faces = limits.max_faces * 4 + 16;
    load_options.external_files = input.external_files;
    ProgressInfo info;
    info.phase = "load";
    sink.report(info);
    const LoadedMesh loaded = load_mesh(input.mesh, input.format, load_options);
    if (loaded.mesh.faces.size() > limits.max_faces)
      throw ApiError("too_many_faces", "the mesh has " + std::to_string(loaded.mesh.faces.size()) +
                                           " faces; this server unfolds at most " +
                                           std::to_string(limits.max_faces));
    if (sink.cancelled()) throw CancelledException();
    throw ApiError("pipeline_unavailable", "this build can load the mesh (" +
                                               std::to_string(loaded.mesh.faces.size()) +
                                               " faces) but has no unfolder yet");
  };
}

}  // namespace papernet::server
