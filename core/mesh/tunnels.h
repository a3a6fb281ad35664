#pragma once

#include <optional>
#include <vector>

#include "core/mesh/mesh.h"

namespace papernet {

/// The shortest loop of `mesh`'s edges, at most `max_length` long, that goes around a tunnel: a
/// simple cycle of interior edges whose cut leaves the faces on its two sides connected (a
/// non-separating loop; a sphere has none, a torus one around its tube and one around its hole).
/// Its vertices in order, the loop closing from the last to the first; none when there is no
/// such loop. Loops through the mesh's boundary are not considered. Edges may be short, the
/// search goes out at most `max_length` / 2 from each vertex.
std::optional<std::vector<int>> shortest_tunnel_loop(const Mesh& mesh, double max_length);

/// `mesh` cut along `loop` (from shortest_tunnel_loop) and each of the two borders closed with a
/// cap: the tunnel is plugged where the loop runs, and the genus falls by one. The faces on one
/// side of the loop get new vertices at the loop's positions; a loop of three edges is closed by
/// one triangle on each side, a longer one by a fan from a new vertex at its centroid. The result
/// is manifold and consistently oriented when `mesh` is; its two caps lie on each other.
Mesh plug_tunnel(const Mesh& mesh, const std::vector<int>& loop);

}  // namespace papernet
