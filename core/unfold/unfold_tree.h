#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh/dual_graph.h"
#include "core/mesh/mesh.h"
#include "core/unfold/net.h"
#include "core/vec.h"

namespace papernet {

/// Intrinsic shape of a triangle, seen from each of its edges: for edge k (corner k to k+1),
/// the third corner lies `along[k]` along the edge from corner k and `left[k]` (> 0) to its left.
struct FaceShape {
  std::array<double, 3> along{};
  std::array<double, 3> left{};
};

/// Shape of face f from its 3D edge lengths.
FaceShape face_shape(const Mesh& mesh, int f);

/// Third corner of a triangle over the 2D edge a->b, on its left (counter-clockwise order a, b, c).
inline Vec2 place_third(Vec2 a, Vec2 b, double along, double left) {
  const Vec2 d = b - a;
  const double inv = 1.0 / norm(d);
  const Vec2 u{d.x * inv, d.y * inv};
  return {a.x + along * u.x - left * u.y, a.y + along * u.y + left * u.x};
}

/// 2D corners of a face whose edge `edge` is glued to edge `other_edge` of an already placed
/// face with corners `other`: the shared corners are copied exactly and the face lies on the
/// far side of the shared edge, counter-clockwise.
inline std::array<Vec2, 3> place_across(const std::array<Vec2, 3>& other, int other_edge, int edge,
                                        const FaceShape& shape) {
  std::array<Vec2, 3> p;
  const Vec2 a = other[(other_edge + 1) % 3], b = other[other_edge];
  p[edge] = a;
  p[(edge + 1) % 3] = b;
  p[(edge + 2) % 3] = place_third(a, b, shape.along[edge], shape.left[edge]);
  return p;
}

/// 2D corners of a root face: corner 0 at the origin, edge 0 along +x, counter-clockwise.
std::array<Vec2, 3> place_root(const Mesh& mesh, int f, const FaceShape& shape);

/// Steepest Edge Unfolder's tree: a random unit direction c is drawn from `seed`; for every vertex
/// but the highest along c, the edge to the neighbour maximising c·(w−v)/|w−v| is a preferred
/// cut. Dual edges are weighted so that preferred cuts are avoided as links (then steep edges
/// over flat ones), and a minimum spanning tree of the dual graph is returned as a parent array
/// (-1 for the root). Works for any genus and for open meshes.
/// \throw InvalidInputException when the dual graph is not connected.
std::vector<int> steepest_edge_tree(const Mesh& mesh, const DualGraph& graph, std::uint64_t seed);

/// Minimum-perimeter tree (Schlickenrieder's heuristic): a maximum spanning tree of the dual
/// graph weighted by edge length, so the cut edges (the net's boundary) are the shortest ones.
/// Long slivers of CAD meshes then stay glued along their long sides. The root is drawn from
/// `seed`. \throw InvalidInputException when the dual graph is not connected.
std::vector<int> min_perimeter_tree(const Mesh& mesh, const DualGraph& graph, std::uint64_t seed);

}  // namespace papernet
