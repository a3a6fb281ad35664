#pragma once

#include <cstddef>

#include "core/mesh/mesh.h"

namespace papernet {

/// Flips edges of `mesh` where that makes thin faces (a height over their longest edge under
/// `min_height`, slivers with a corner almost on the opposite edge) thicker: the two faces at an
/// edge become the two at the other diagonal of their quadrilateral when the lower of the two new
/// heights is greater than the lower of the two old, the diagonal is not an edge already, neither
/// new face turns over, and the surface stays within `max_move` of `mesh`'s (a flip moves it at
/// most the distance from the flipped edge of the nearer of the two other corners, and the flips
/// that made a face add up). Passes over the edges until none flips. Vertices stay where they are;
/// the result is manifold and oriented when `mesh` is. Returns the number of flips.
std::size_t thicken_thin_faces(Mesh& mesh, double min_height, double max_move);

/// A face's height over its longest edge (0 for a degenerate face).
double face_height(const Mesh& mesh, int face);

}  // namespace papernet
