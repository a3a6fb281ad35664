#pragma once

#include <cstddef>

#include "server/job.h"

namespace papernet::server {

struct PipelineLimits {
  std::size_t max_bytes = std::size_t{64} << 20;
  std::size_t max_faces = 1'000'000;
};

/// The real job: load (core/load), validate (core/validate; 422 with reasons), unfold (TU:
/// unfold_tabu; QQ/SEMP/SEQ: unfold_progressive, which may end approximate), check the net
/// (core/net_check), write net JSON, SVG, PDF and GLB. Progress phases: load, validate, the
/// unfolder's (collapse, unfold, uncollapse), tabs (tab mode auto: cuts changed so that glue
/// tabs fit), write. Intermediate overlap-free nets are
/// rendered at most every two seconds and handed to the sink.
JobRunner make_pipeline_runner(PipelineLimits limits);

}  // namespace papernet::server
