#pragma once

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/vec.h"

namespace papernet {

/// A face that a vertex split puts back.
struct SplitFace {
  int face = -1;                 ///< id in the input mesh
  std::array<int, 3> corners{};  ///< its corners after the split (input vertex ids)
  /// The faces across its two edges that do not belong to the collapsed edge: wing[0] shares the
  /// edge (split.vertex, w), wing[1] the edge (split.moved, w), w being its third corner; -1 on a
  /// boundary. Before the split, wing[0] and wing[1] were neighbours across (split.moved, w):
  /// when they are linked in an unfold tree, this face goes between them.
  std::array<int, 2> wing{-1, -1};
};

/// One vertex split: it undoes one edge collapse, exactly. All ids are the input mesh's.
struct VertexSplit {
  int vertex = -1;                   ///< vertex that comes back (it was removed by the collapse)
  Vec3 vertex_position;              ///< its position (the input's, never changed)
  int moved = -1;                    ///< vertex that stayed and moves back
  Vec3 moved_from;                   ///< `moved`'s position before the split
  Vec3 moved_to;                     ///< `moved`'s position after the split
  std::vector<SplitFace> new_faces;  ///< 1 (boundary edge) or 2 faces re-inserted
  /// Existing faces whose corner `second` changes from `moved` back to `vertex`.
  std::vector<std::pair<int, int>> relabelled;
  /// Every existing face whose shape changes (all faces around `moved` and `vertex` after the
  /// split, new faces excluded; includes the relabelled ones).
  std::vector<int> reshaped;
};

/// An edge-collapse hierarchy over a manifold, consistently oriented triangle mesh that keeps the
/// input's vertex and face ids: collapsed faces and vertices are marked removed, never renumbered.
/// Splitting all recorded collapses in reverse order gives back the input element for element,
/// positions bit for bit.
class ProgressiveMesh {
 public:
  /// \throw InvalidInputException when `mesh` is not a manifold, consistently oriented triangle
  /// mesh without repeated corners (names the first fault).
  explicit ProgressiveMesh(Mesh mesh);

  /// The current state in the input's ids. Entries of removed faces and vertices are stale.
  const Mesh& mesh() const { return mesh_; }
  bool face_alive(int f) const { return face_alive_[f] != 0; }
  bool vertex_alive(int v) const { return !vertex_faces_[v].empty(); }
  std::size_t face_count() const { return face_count_; }
  std::size_t vertex_count() const { return vertex_count_; }
  std::size_t input_face_count() const { return mesh_.faces.size(); }
  /// Faces currently around vertex v (unordered).
  const std::vector<int>& vertex_faces(int v) const { return vertex_faces_[v]; }

  /// Genus of the input, from V - E + F = 2 - 2g - b with b boundary loops.
  int genus() const { return genus_; }
  int boundary_loops() const { return boundary_loops_; }

  /// True when collapsing `vertex` into `kept` (which then moves to `position`) keeps the mesh a
  /// manifold (link condition, no non-manifold boundary vertex, no duplicate face, at least
  /// one face left), flips no face normal, makes no face degenerate (height below 1e-6 of its
  /// longest edge) and leaves at most 24 faces around `kept`.
  bool can_collapse(int vertex, int kept, Vec3 position) const;
  /// Applies that collapse and records it. \throw TopologyException when !can_collapse.
  void collapse(int vertex, int kept, Vec3 position);
  /// Applies that collapse and records it when can_collapse, and returns true; otherwise changes
  /// nothing and returns false (one legality check instead of two).
  bool try_collapse(int vertex, int kept, Vec3 position);

  /// Number of recorded collapses not yet undone.
  std::size_t splits_left() const { return splits_.size(); }
  /// The split that `split()` applies next. \pre splits_left() > 0
  const VertexSplit& next_split() const { return splits_.back(); }
  /// Undoes the last remaining collapse and returns what it changed (valid until the next
  /// collapse). \pre splits_left() > 0
  VertexSplit split();

  /// The current state as a compact Mesh; `face_ids[i]` / `vertex_ids[i]` receive the input id
  /// of its face / vertex i (vertex order follows the input's ids, face order too).
  Mesh compact(std::vector<int>* face_ids = nullptr, std::vector<int>* vertex_ids = nullptr) const;

 private:
  bool is_boundary_edge(int a, int b) const;
  bool is_boundary_vertex(int v) const;
  int face_across(int f, int a, int b) const;

  Mesh mesh_;
  std::vector<std::vector<int>> vertex_faces_;
  std::vector<char> face_alive_;
  std::vector<VertexSplit> splits_;
  std::size_t face_count_ = 0;
  std::size_t vertex_count_ = 0;
  int genus_ = 0;
  int boundary_loops_ = 0;
};

}  // namespace papernet
