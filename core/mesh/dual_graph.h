#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh/mesh.h"

namespace papernet {

/// Face adjacency of a triangle mesh (its dual graph). Edge k of face f runs from corner k to
/// corner k+1 (mod 3). `neighbour[f][k]` is the face across that edge, -1 on a boundary edge;
/// `neighbour_edge[f][k]` is the index of the same edge in the neighbour (-1 on a boundary).
struct DualGraph {
  std::vector<std::array<int, 3>> neighbour;
  std::vector<std::array<std::int8_t, 3>> neighbour_edge;

  /// Number of dual edges (interior mesh edges).
  std::size_t edge_count() const;
  /// Number of connected components of the dual graph (0 for an empty mesh).
  std::size_t component_count() const;
  /// True when the faces are connected and their adjacency has no cycle: the unfold tree is the
  /// whole dual graph, so the mesh has a single edge unfolding.
  bool is_tree() const;
};

/// Builds the dual graph of `mesh`.
/// \throw InvalidInputException when a vertex index is out of range, a face repeats a vertex,
///        an edge is used by more than two faces, or two faces that share an edge are oriented
///        inconsistently. The message names the face and the edge.
DualGraph build_dual_graph(const Mesh& mesh);

/// 1 for each vertex of `mesh` on a boundary edge (an edge with a face on one side only), else 0;
/// `graph` is mesh's dual graph.
std::vector<char> boundary_vertices(const Mesh& mesh, const DualGraph& graph);

/// Key of the directed edge a->b, for hash maps over half-edges.
inline std::uint64_t half_edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

/// Key of the undirected edge {a, b}, for hash maps over edges: half_edge_key from its lower end.
inline std::uint64_t edge_key(int a, int b) {
  return a < b ? half_edge_key(a, b) : half_edge_key(b, a);
}

}  // namespace papernet
