#pragma once

#include <cstddef>
#include <optional>

#include "core/mesh/decimate.h"
#include "core/mesh/mesh.h"
#include "core/progress.h"

namespace papernet {

/// A low-poly version of `mesh` to print instead of it: collapsed with `strategy` (legal
/// collapses only, as decimate) to at most `faces` faces, or as far as legal collapses go, with
/// ids of its own. None when that is not fewer faces than `mesh` (`faces` 0 or not below its
/// count, or no legal collapse): then print `mesh` itself. Fewer, larger faces have sharper
/// vertices and longer edges, so more cut edges have room for a glue tab (docs/tabs.md).
/// Reports phase "collapse".
/// \throw InvalidInputException when `mesh` is not a manifold, oriented triangle mesh.
/// \throw CancelledException when `progress` asks to stop.
std::optional<Mesh> simplify_mesh(const Mesh& mesh, CollapseStrategy strategy, std::size_t faces,
                                  Progress& progress);

}  // namespace papernet
