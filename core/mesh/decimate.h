#pragma once

#include <cstddef>
#include <string>

#include "core/mesh/mesh.h"
#include "core/mesh/progressive_mesh.h"
#include "core/progress.h"

namespace papernet {

/// Edge-collapse strategies, named as in the paper (selection / placement).
enum class CollapseStrategy {
  QQ,    ///< quadric error selection, quadric-optimal placement (Garland-Heckbert)
  SEMP,  ///< shortest edge first, midpoint placement
  SEQ,   ///< shortest edge first, quadric-optimal placement
};

/// "QQ", "SEMP", "SEQ". (The job's strategies, TU among them, are api/options.h's Strategy.)
std::string collapse_strategy_name(CollapseStrategy strategy);

/// The paper's collapse target t_f = i_f/10 + sqrt(i_f)·(1+g), rounded to the nearest integer.
std::size_t collapse_target(std::size_t input_faces, int genus);

struct DecimateOptions {
  CollapseStrategy strategy = CollapseStrategy::QQ;
  /// Face count to collapse to; 0 means collapse_target(faces, genus).
  std::size_t target_faces = 0;
  /// Reuse a vertex's candidate evaluations whose two ends have not changed since it was last
  /// queued (the same collapses either way; false evaluates everything again, for tests).
  bool reuse_evaluations = true;
};

/// Collapses `mesh` with legal collapses only (see ProgressiveMesh::can_collapse) until it has at
/// most the target face count or no legal collapse is left, and returns the hierarchy whose
/// splits restore `mesh` exactly. Reports phase "collapse" through `progress`.
/// Our own loop on our own connectivity (ProgressiveMesh), not a library's decimater: the
/// unfolder needs ids kept through every collapse and split and bit-exact undo
/// (docs/architecture.md, "Dependencies").
/// \throw InvalidInputException when `mesh` is not a manifold, oriented triangle mesh.
/// \throw CancelledException when `progress` asks to stop.
ProgressiveMesh decimate(const Mesh& mesh, const DecimateOptions& options, Progress& progress);

/// Collapses `pm` further, to at most `target_faces` faces or until no legal collapse is left,
/// with quadrics of its current state. Collapses already recorded stay, so splitting everything
/// still restores the input exactly. Reports nothing; polls `progress` for cancellation.
/// \throw CancelledException when `progress` asks to stop.
void collapse_further(ProgressiveMesh& pm, CollapseStrategy strategy, std::size_t target_faces,
                      Progress& progress);

}  // namespace papernet
