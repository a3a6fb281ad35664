// Internal to the tab clearance pass (core/tabs/tab_clearance*.cpp): the search state, a net
// whose cuts change by edge swaps of its unfold tree. Not part of the public API.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/progress.h"
#include "core/tabs/internal/pass_progress.h"
#include "core/tabs/internal/tab_clearance_params.h"
#include "core/tabs/tab_clearance.h"
#include "core/unfold/folds.h"
#include "core/unfold/net.h"
#include "core/unfold/overlap.h"
#include "core/unfold/overlap_grid.h"
#include "core/unfold/unfold_tree.h"

namespace papernet::tab_clearance_detail {

class Clearance {
 public:
  Clearance(const Mesh& mesh, const Net& net, const TabClearanceOptions& options);
  std::size_t blocked_count() const { return blocked_count_; }
  std::vector<EdgeSide> blocked_edges() const;
  /// The tabu search (tab_clearance_search.cpp); reports to `progress` the pass's evaluations:
  /// `evaluations_before` and this search's.
  void run(PassProgress& progress, std::size_t evaluations_before = 0);
  /// The tree links across edges at vertex a, each once, as (face, edge) on the face with the
  /// smaller index.
  std::vector<std::pair<int, int>> links_at(int a) const;
  /// For kicks: the kKickGlues cut edges nearest to vertex w across tree link (lf, lk) whose
  /// gluing (with the link cut) leaves no new flat leaf of the cut tree (crossing_glues).
  std::vector<std::pair<int, int>> kick_glues(int lf, int lk, int w) const;
  /// The unfold tree (parent by face) with tree link (lf, lk) cut and cut edge (cf, ck) glued:
  /// the side cut off is re-rooted at the glued edge's face on that side.
  std::vector<int> swapped_tree(int lf, int lk, int cf, int ck) const;
  int neighbour(int f, int k) const { return adj_[f][k]; }
  const std::vector<int>& faces_at(int v) const { return vertex_faces_[v]; }
  Net net() const { return Net{parent_, pos_}; }
  std::size_t moves_ = 0, evaluations_ = 0, compound_moves_ = 0;
  bool compound_ = true;
  /// When not empty, run() visits only the blocked edges marked here (by canonical half-edge
  /// 3 * f + k, as blocked_edges() names them): a kick's search looks where the kick changed
  /// the net.
  std::vector<char> focus_;
  /// Lets run() go on from the best net: `evaluations` more, within `seconds` (when limited).
  void extend(std::size_t evaluations, double seconds) {
    budget_ += evaluations;
    if (time_limit_ > 0) time_limit_ = std::max(seconds, 1e-9);
  }

 private:
  int canon(int f, int k) const {
    const int n = adj_[f][k];
    return n < 0 || f < n ? 3 * f + k : 3 * n + adj_edge_[f][k];
  }
  bool linked(int f, int k) const { return links_[f] >> k & 1; }
  /// Edge k of face f was changed by a recent move of run() (for kTenure steps).
  bool tabu(int f, int k) const { return tabu_until_[canon(f, k)] > step_; }
  bool coincident(int f, int k) const;
  bool is_cut(int f, int k) const { return adj_[f][k] >= 0 && !linked(f, k) && !coincident(f, k); }
  bool side_has_room(int f, int k) const {
    return room_beside(
        pos_[f], k, [](int) { return false; },
        [](const Triangle2&, const Triangle2&, const Box2&) { return false; });
  }
  /// Whether a tab fits on the outside of edge k of triangle `face` (tab_fits): the faces in the
  /// grid are obstacles where they are, except those `skip(c)` leaves out, and `more(t0, t1,
  /// box)` says whether a tab's two triangles meet another obstacle.
  template <class Skip, class More>
  bool room_beside(const Triangle2& face, int k, Skip&& skip, More&& more) const {
    return tab_fits(
        face, k, shapes_, height_, [&](const Triangle2& t0, const Triangle2& t1, const Box2& box) {
          bool hit = false;
          const Box2 b0 = triangle_box(t0), b1 = triangle_box(t1);
          grid_.query(box, [&](int c) {
            // triangles_overlap's own first test on each triangle, with the faces' boxes kept
            // (box_ is the box of pos_ for every face not skipped); a face whose box misses the
            // tab's misses both its triangles.
            if (hit || !boxes_overlap(box, box_[c], tol_) || skip(c)) return;
            const Box2& bc = box_[c];
            hit = (boxes_overlap(b0, bc, tol_) && triangles_overlap_in_boxes(t0, pos_[c], tol_)) ||
                  (boxes_overlap(b1, bc, tol_) && triangles_overlap_in_boxes(t1, pos_[c], tol_));
          });
          return hit || more(t0, t1, box);
        });
  }
  bool blocked(int f, int k) const {
    return is_cut(f, k) && !side_has_room(f, k) && !side_has_room(adj_[f][k], adj_edge_[f][k]);
  }
  /// parent_, tin_, size_ and order_ from the links: the tree rooted at face 0, in pre-order.
  void root_tree();
  /// blocked(f, k) once the move apply_move laid out (moving_, new_pos_, slot_, the links
  /// swapped) is made, before its faces move in the grid; kUnknown when more than
  /// kNearMovedFaces moved faces come near the edge (then blocked() after the move tells).
  enum class Blocked { kNo, kYes, kUnknown };
  Blocked blocked_when_moved(int f, int k);
  /// The same after one swap that commit() made (cut link lk of face lf, glued edge ck of face
  /// cf), from the tree before it: the side cut off is rooted again at the glued edge and its
  /// block of the pre-order moved after its new parent. Work in that side's size, the depth of
  /// the tree and a shift of the pre-order, not a walk of the whole tree.
  void reroot_after_swap(int lf, int lk, int cf, int ck);
  bool in_sub(int top, int x) const {
    return static_cast<unsigned>(tin_[x] - tin_[top]) < static_cast<unsigned>(size_[top]);
  }
  void set_link(int f, int k, bool on);
  void place(int f, const Triangle2& p);
  /// What a move changes: blocked edges and flat leaves of the cut tree (after - before).
  struct Change {
    long long blocked = 0, flat_leaves = 0;
  };
  bool apply_move(int tf, int tk, int lf, int lk, int cf, int ck, Change& out);
  bool apply_compound(int tf, int tk, const std::vector<std::array<int, 4>>& swaps, int root,
                      Change& out);
  void recount(Change& out);
  std::vector<int> hair_path(int u, int v) const;
  /// The best compound move try_compound found that does not lower the blocked count and closes
  /// at most max_blocked edges: the search's sideways move when it beats the best single swap.
  struct Sideways {
    long long max_blocked = 0;
    Change change;
    std::vector<std::array<int, 4>> swaps;
    int root = 0;
  };
  bool try_compound(int f, int k, Sideways* sideways);
  void undo();
  void commit();
  template <class Consider>
  bool candidates(int f, int k, Consider&& consider);
  /// The cut edges (face, edge) between the two sides of tree link `top` that gluing could
  /// replace it by without a new flat leaf of the cut tree, given that cutting the link adds a
  /// cut edge at `link_ends` and that `degree(x)` is the cut degree of vertex x: nearest to
  /// `at` first, at most `most`; `skip(face, edge)` leaves out more.
  template <class Degree, class Skip>
  std::vector<std::pair<int, int>> crossing_glues(int top, std::array<int, 2> link_ends, Vec3 at,
                                                  std::size_t most, Degree&& degree,
                                                  Skip&& skip) const;
  /// crossing_glues for a link of a tree given by its two sides rather than by the current
  /// tree's subtree: `sub(x)` says whether face x is on the side without face 0, `sub_small`
  /// whether that side is the smaller one (the side moved), `small_faces(f)` calls f on each
  /// face of the smaller side.
  template <class Sub, class SmallFaces, class Degree, class Skip>
  std::vector<std::pair<int, int>> crossing_glues(Sub&& sub, bool sub_small,
                                                  SmallFaces&& small_faces,
                                                  std::array<int, 2> link_ends, Vec3 at,
                                                  std::size_t most, Degree&& degree,
                                                  Skip&& skip) const;
  /// The current tree without the links above tops[0], ..., tops[n - 1] (each named by the face
  /// below it) falls into n + 1 parts: part 0 holds face 0 (the tree's root), part i + 1 the
  /// faces whose nearest cut link on the way to face 0 is the one above tops[i].
  int part_of(const int* tops, int n, int x) const {
    int part = 0;
    for (int i = 0; i < n; ++i)
      if (in_sub(tops[i], x) && (part == 0 || size_[tops[i]] < size_[tops[part - 1]])) part = i + 1;
    return part;
  }
  /// Calls f(x) for each face x of the parts (numbered as part_of does) for which want(part)
  /// holds, in the tree's pre-order: the work is that of those parts, not of the whole tree.
  template <class Want, class F>
  void for_each_in_parts(const int* tops, int n, Want&& want, F&& f) const {
    // Between consecutive ends of the tops' ranges in the pre-order, every face is in one part.
    std::vector<int> ends{0, nf_};
    for (int i = 0; i < n; ++i)
      ends.push_back(tin_[tops[i]]), ends.push_back(tin_[tops[i]] + size_[tops[i]]);
    std::sort(ends.begin(), ends.end());
    for (std::size_t e = 0; e + 1 < ends.size(); ++e) {
      const int lo = ends[e], hi = ends[e + 1];
      if (lo == hi || !want(part_of(tops, n, order_[lo]))) continue;
      for (int i = lo; i < hi; ++i) f(order_[i]);
    }
  }
  std::vector<int> cut_neighbours(int x) const;
  std::vector<std::pair<int, int>> hair_links(int u, int v) const;
  /// A leaf of the cut tree at v does no harm: v is on the boundary or far from flat.
  bool harmless(int v) const { return vboundary_[v] || std::abs(defect_[v]) >= kSharpDefect; }

  const Mesh& mesh_;
  int nf_ = 0;
  std::vector<std::array<int, 3>> adj_;
  std::vector<std::array<std::int8_t, 3>> adj_edge_;
  std::vector<FaceShape> shape_;
  std::vector<std::vector<int>> vertex_faces_;
  std::vector<Triangle2> pos_;
  std::vector<Box2> box_;
  std::vector<std::uint8_t> links_;
  OverlapGrid grid_;
  double tol_ = 0, height_ = 0;
  std::size_t budget_ = 0;
  double time_limit_ = 0;              // seconds; <= 0: none
  double seconds_per_blocked_ = 0;     // TabClearanceOptions::seconds_per_blocked_edge
  std::size_t step_limit_ = 0;         // evaluations_ allowed up to in the current step of run()
  std::size_t far_glues_ = kFarGlues;  // cut edges farther along the cut tree tried per link
  bool endgame_ = false;               // after the first restart (see run): hair links too
  bool keep_bounds_ = true;
  Box2 bounds_;  // of the input net
  std::vector<TabShape> shapes_;
  std::vector<char> blocked_;  // by canonical half-edge 3 * f + k
  std::size_t blocked_count_ = 0;
  std::vector<int> parent_, tin_, size_, order_;
  std::vector<double> defect_;               // angle defect by vertex (0 on the boundary)
  std::vector<char> vboundary_;              // vertex on the mesh's boundary
  std::vector<int> cut_degree_;              // cut edges (unlinked interior edges) at each vertex
  std::vector<std::array<int, 4>> pending_;  // the applied move's swaps: lf, lk, cf, ck
  std::uint32_t step_ = 0;                   // run()'s current step (tabu_until_)
  std::vector<std::uint32_t> tabu_until_;    // by canonical half-edge: step until which it stays

  // Scratch of the moves (apply_move, apply_compound, reroot_after_swap).
  std::vector<int> moving_, from_, mark_, slot_, tops_, block_, stack_, near_;
  std::vector<std::pair<int, int>> glues_;  // apply_compound: the edges its swaps glue
  std::vector<char> is_moving_;
  std::vector<Triangle2> new_pos_, old_pos_;
  std::vector<int> affected_;
  std::vector<std::pair<int, int>> ends_;  // vertex, change of its cut degree
  std::vector<std::uint32_t> stamp_;
  std::uint32_t epoch_ = 0;
};

}  // namespace papernet::tab_clearance_detail
