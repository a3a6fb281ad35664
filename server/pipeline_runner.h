#pragma once

#include "engine/pipeline.h"
#include "server/job.h"

namespace papernet::server {

/// The real job: the engine's pipeline (engine/pipeline.h) with the service's limits, writing the
/// net JSON, SVG, PDF and GLB a job serves. Progress phases: load, validate, the unfolder's
/// (collapse, unfold, uncollapse), tabs, write. Intermediate overlap-free nets, rendered at most
/// every two seconds, go to the sink. Failures become the problems clients see: invalid_mesh
/// with the validator's reasons, unfold_failed, too_many_faces, and so on (server/problem.h).
JobRunner make_pipeline_runner(PipelineLimits limits);

}  // namespace papernet::server
