#pragma once

#include <cstddef>

#include "server/job.h"

namespace papernet::server {

struct PipelineLimits {
  std::size_t max_bytes = std::size_t{64} << 20;
  std::size_t max_faces = 1'000'000;
};

/// The real job: load (core/load), validate, unfold progressively, write net JSON/SVG/PDF and
/// GLB. Pieces that are not in this build make the job fail with pipeline_unavailable; the
/// runner never pretends to have produced a net.
JobRunner make_pipeline_runner(PipelineLimits limits);

}  // namespace papernet::server
