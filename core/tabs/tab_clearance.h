#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/progress.h"
#include "core/tabs/tab_clearance_options.h"
#include "core/unfold/folds.h"
#include "core/unfold/net.h"
#include "core/unfold/overlap.h"
#include "core/vec.h"

namespace papernet {

/// A glue tab's shape relative to its edge: the stretch [from, to] of the edge (fractions from
/// the side's first point) its base covers and the slant of each end, as its tangent (computed
/// once by tab_shapes: the room tests build millions of tabs).
struct TabShape {
  double from = 0, to = 1;
  double tan0 = 1, tan1 = 1;  ///< 45 degrees
};

/// The tab shapes a printed net may use, best first: bases over the whole edge and over
/// stretches of it (at least 40 %), ends slanted by `angle_deg` or 40 % of it.
std::vector<TabShape> tab_shapes(double angle_deg);

/// The trapezoid of `shape` on the outside of edge k of the counter-clockwise triangle `face`,
/// `height` tall, counter-clockwise: the base's two ends (the one nearer corner k second), then
/// the two top corners. The ends' insets shrink together so the top keeps a tenth of the base.
std::array<Vec2, 4> tab_trapezoid(const std::array<Vec2, 3>& face, int k, const TabShape& shape,
                                  double height);

/// Whether a tab of one of `shapes`, `min_height` tall (half the edge on shorter edges), fits on
/// the outside of edge k of `face`: `hits(t0, t1, box)` says whether the tab's two triangles
/// (their bounding box `box`) overlap an obstacle. False on an edge of length 0. The one room
/// test of the pass (against the net), of leaf_room (against a fan) and of the print's pieces
/// grown with room for tabs (print/grow.h, grow_to_fit).
template <class Hits>
bool tab_fits(const Triangle2& face, int k, const std::vector<TabShape>& shapes, double min_height,
              Hits&& hits) {
  const double len = norm(face[(k + 1) % 3] - face[k]);
  if (!(len > 0)) return false;
  const double h = std::min(min_height, 0.5 * len);
  for (const TabShape& shape : shapes) {
    const auto t = tab_trapezoid(face, k, shape, h);
    const Triangle2 t0{t[0], t[1], t[2]}, t1{t[0], t[2], t[3]};
    Box2 box = triangle_box(t0);
    box.add(t[3]);
    if (!hits(t0, t1, box)) return true;
  }
  return false;
}

/// Interior cut edges of `net` where no tab of `options.min_height` (of any of tab_shapes)
/// fits on either side without overlapping a face; each edge once, as its side on the face with
/// the smaller index. Edges whose two sides lie on each other (glued without a tree link) are
/// not cut. Tabs are not obstacles here: this is room, not a placement.
std::vector<EdgeSide> edges_without_tab_room(const Mesh& mesh, const Net& net,
                                             const TabClearanceOptions& options);

struct TabClearanceResult {
  Net net;
  std::size_t blocked_before = 0;  ///< cut edges without tab room in the input net
  std::size_t blocked_after = 0;   ///< ... and in `net`
  std::size_t moves = 0;           ///< moves from the input to `net`
  std::size_t evaluations = 0;     ///< candidate moves evaluated (kicks included)
  std::size_t compound_moves = 0;  ///< compound moves among `moves` (each counts two there)
  std::size_t kicks = 0;           ///< kicks that made `net` better (see clear_tab_room)
  bool searched_on = false;        ///< the second round was more of the tabu search
  /// The cut edges of `net` without room (edges_without_tab_room), when the pass knows them
  /// without looking again (not after a kick).
  std::optional<std::vector<EdgeSide>> blocked;
};

/// Makes room for tabs: changes which edges of an overlap-free `net` are cut so that fewer cut
/// edges lack room for a tab (edges_without_tab_room). A move cuts a tree link at an end of
/// such an edge (typically at a leaf of the cut tree, where the edge's two sides lie a few
/// degrees apart around an almost flat vertex) and glues a cut edge on the cycle that link
/// closes, rotating the smaller side of the tree rigidly; a move that overlaps is never made.
/// Where no such swap helps, a compound move re-hangs the hair the edge lies on (the path of cut
/// edges from a leaf at a flat vertex): two swaps checked for overlap together. A
/// tabu search over these moves (it also makes moves that close other edges, to get out of
/// local minima) returns the net with the fewest edges without room it has seen: an
/// overlap-free net of the same mesh (glued edges copied exactly), never worse than the input,
/// or the input itself when nothing helped. Then a second round, as long again: when the search
/// spent its budget with many edges (more than 64) still without room it goes on; else kicks get
/// it out of where it stalled (every swap that opens an edge overlaps): such a swap is made
/// anyway, the unfolder's local repair (Unfolding::repair_locally) removes the overlaps, and a
/// short tabu search from the repaired net replaces the result when it ends with fewer edges
/// without room. Deterministic (unless options.time_limit_seconds stops it). Progress: phase
/// "tabs", at most every 50 ms and once at the end (phase_fraction 1), with the candidate moves
/// evaluated (`iterations`) and the share of the pass done (`phase_fraction`: of both rounds'
/// budget, or of the time limit when that is further along).
/// \pre `net` is an overlap-free net of `mesh` (check_net passes).
/// \throw CancelledException when `progress` asks to stop.
TabClearanceResult clear_tab_room(const Mesh& mesh, const Net& net,
                                  const TabClearanceOptions& options, Progress& progress);

}  // namespace papernet
