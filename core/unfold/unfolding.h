#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/progress.h"
#include "core/unfold/internal/unfolding_state.h"
#include "core/unfold/local_repair.h"
#include "core/unfold/net.h"
#include "core/unfold/overlap.h"
#include "core/unfold/tabu.h"

namespace papernet {

/// The incremental state of an edge unfolding: mesh, unfold tree, 2D layout, spatial index and
/// the set of overlapping face pairs. Both the plain Tabu Unfolder and progressive unfolding
/// drive this one state; nothing that did not move is recomputed.
///
/// Each face has its own 2D triangle; a child is placed across the edge it shares with its
/// parent, counter-clockwise (docs/architecture.md, "The unfolder"). Two faces overlap when their
/// interiors intersect by more than kOverlapTolerance of the mesh's bounding-box diagonal.
///
/// Growing the mesh (vertex splits): change vertices and faces with add_vertex,
/// set_vertex_position, set_face_corners and add_face; fix the tree with attach and
/// insert_between; then call update() once, which rebuilds the adjacency of what changed,
/// re-lays out only the faces whose position changed and tests only those for new overlaps.
/// Between those edits and update() the layout and overlap queries are stale.
class Unfolding : private unfolding_detail::UnfoldingState {
 public:
  /// Builds the state from a mesh and an unfold tree (`parent[f]` is the face f hangs from,
  /// -1 for the root; each link joins faces sharing an edge).
  /// \throw InvalidInputException for a non-manifold or inconsistently oriented mesh.
  /// \throw TopologyException when `parent` is not a spanning tree of adjacent faces.
  Unfolding(Mesh mesh, const std::vector<int>& parent);

  /// Builds the state from the Steepest Edge Unfolder's tree (see steepest_edge_tree).
  static Unfolding steepest_edge(Mesh mesh, std::uint64_t seed);

  const Mesh& mesh() const { return mesh_; }
  std::size_t face_count() const { return mesh_.faces.size(); }
  /// Number of overlapping face pairs.
  std::size_t overlap_count() const { return pair_count_; }
  /// Faces that overlap at least one other face, in no particular order.
  const std::vector<int>& overlapping_faces() const { return overlapping_; }
  /// Parent of f in the unfold tree (-1 for the root). The root changes as the tree is re-rooted;
  /// re-rooting never moves a face.
  int parent(int f) const { return parent_[f]; }
  /// Face across edge k (corner k to k+1) of f, -1 on a boundary.
  int neighbour(int f, int k) const { return adj_[f][k]; }
  /// 2D corners of f: points(f)[k] is where mesh().faces[f][k] lands.
  const Triangle2& points(int f) const { return pos_[f]; }
  /// The net of the current state.
  Net net() const { return Net{parent_, pos_}; }
  /// Length below which 2D differences are ignored by the overlap test.
  double tolerance() const { return tolerance_; }

  /// Runs the Tabu Unfolder (docs/architecture.md) on the current state until no overlaps remain or
  /// the budget is spent. Returns true when the state is overlap-free. Reports progress (overlaps
  /// left, iterations) through `progress`; \throw CancelledException when it asks to stop.
  bool resolve_overlaps(const TabuOptions& options, Progress& progress, TabuStats* stats = nullptr);

  /// Removes overlaps by local moves: for an overlapping pair, a link on the tree path between
  /// the two faces is cut where one side has few faces (at most `options.max_side`), and that
  /// side is glued back along another of its edges (any face of it, any edge to the rest); the
  /// move that lowers the overlap count most is applied, until none is left or no such move
  /// lowers it. Deterministic; costs O(side) per evaluated move, never O(|F|). The moved side is
  /// laid out exactly from its new parent. Returns the overlap count left (0: overlap-free).
  std::size_t repair_locally(const LocalRepairOptions& options, LocalRepairStats* stats = nullptr);

  // ---- Editing for uncollapse steps (then call update()) ----

  /// Appends a vertex; returns its index.
  int add_vertex(Vec3 position);
  /// Moves vertex v in 3D: every face using it changes shape and is re-laid out by update().
  void set_vertex_position(int v, Vec3 position);
  /// Replaces the corners of an existing face (counter-clockwise from outside).
  void set_face_corners(int f, std::array<int, 3> corners);
  /// Appends a face, not yet in the tree: give it a place with attach or insert_between before
  /// update(). Returns its index (faces are numbered in order of addition).
  int add_face(std::array<int, 3> corners);
  /// Hangs face f from `parent` (they must share an edge when update() runs); f's own subtree,
  /// if any, comes along.
  void attach(int f, int parent);
  /// Puts face f between two linked faces a and b: a - f - b. The pair may be linked in either
  /// direction (the root moves as the Tabu Unfolder re-roots). f must share an edge with both
  /// when update() runs and must not be in the tree yet.
  void insert_between(int f, int a, int b);
  /// True when faces a and b are linked in the unfold tree (in either direction).
  bool linked(int a, int b) const { return parent_[a] == b || parent_[b] == a; }
  /// Applies the edits: rebuilds adjacency around changed faces, re-roots the tree in the
  /// largest part that did not change, re-lays out every other face and tests exactly those
  /// for overlaps. Returns the overlap count.
  /// \throw TopologyException naming the fault when the edits left a non-manifold mesh, a face
  ///        outside the tree or a link between faces that share no edge; the state is then
  ///        unusable (keep a copy of the last good one: Unfolding is copyable).
  std::size_t update();
  /// Faces update() has re-laid out (and tested), summed over all its calls.
  std::size_t relaid_faces() const { return relaid_; }

 private:
  friend struct UnfoldingTestAccess;  // tests/unfold_test.cpp: the Tabu move primitives

  // unfolding.cpp: construction, editing, update.
  void set_adjacency(int f);
  int edge_to(int f, int other) const;
  void reroot(int r);
  void add_pair(int a, int b);
  void remove_pair(int a, int b);
  void sort_overlapping();
  // Adds a pair for every face in the grid that overlaps face f (at pos_[f], box_[f]).
  void add_pairs_in_grid(int f);
  void test_moved(const std::vector<int>& moved);
  bool update_locally(const std::vector<int>& around, std::vector<int>& moved);

  // unfolding_moves.cpp: the move primitives of the Tabu Unfolder.
  void root_at(int r);
  // The faces reached from r over links without crossing to parent_[r], in root_at's pre-order,
  // into out; sets their parents and subtree sizes.
  void preorder_from(int r, std::vector<int>& out);
  // True when x is in a's subtree in the pre-order of root_at.
  bool in_subtree_of(int a, int x) const {
    return static_cast<unsigned>(tin_[x] - tin_[a]) < static_cast<unsigned>(size_[a]);
  }
  // Next face on the tree path from g towards face r (g != r), from the pre-order of root_at.
  int step_towards(int g, int r) const;
  // Cuts the link between g and its neighbour `other` on the walk (its parent as the walk sees
  // the tree, which need not be parent_[g]).
  void cut(int g, int other);
  bool in_range(int x) const {
    return static_cast<unsigned>(tin_[x] - cut_lo_) < static_cast<unsigned>(cut_hi_ - cut_lo_);
  }
  // True when x is on g's side of the cut (g's subtree as the walk sees the tree).
  bool in_subtree(int x) const { return in_range(x) == g_in_range_; }
  bool in_small(int x) const { return in_range(x) == small_is_range_; }
  int move_anchor(int g, int k, Triangle2& anchor_pos, Rigid& motion) const;
  long long crossing_pairs() const;  // overlapping pairs between the two sides of the cut
  // Calls f(a, b) for each overlapping pair with a on the cut's smaller side, b on the other.
  template <class F>
  void for_each_crossing(F&& f) const;
  long long evaluate_move(int g, int k, long long crossing, long long cutoff);
  void apply_move(int g, int k);
  void move_subtree(int g, int q);
  void rehang_range(int g, int q);
  void relayout_all();
  std::uint32_t next_seen_epoch();

  // unfolding_repair.cpp: local repair.
  std::uint32_t next_side_epoch();
  void breadth_first_side(int x, int y, std::size_t count, std::vector<std::uint32_t>& mark,
                          std::uint32_t epoch, std::vector<int>& out) const;
  bool collect_side(int x, int y, std::size_t limit);
  bool grow_side(int x, int y, int inner, std::size_t limit);
  void near_faces(int x, int y, std::size_t count);
  // The tree path a .. b into path_.
  void tree_path(int a, int b);
};

}  // namespace papernet
