#pragma once

#include <array>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/vec.h"

namespace papernet {

/// An edge unfolding of a Mesh: every face has its own 2D triangle, and the faces form a tree
/// (the unfold tree) in which each face hangs from a parent it shares an edge with.
/// `points[f][k]` is where vertex `mesh.faces[f][k]` lands; `parent[f]` is -1 for the root only.
struct Net {
  std::vector<int> parent;
  std::vector<std::array<Vec2, 3>> points;
};

}  // namespace papernet
