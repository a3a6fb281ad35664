#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "core/unfold/folds.h"
#include "core/vec.h"

namespace papernet {

/// A glue tab: a trapezoid on the outside of one side of a cut edge. `corners` are
/// counter-clockwise: the two ends of its base, which lies on the edge (corners[1] nearer the
/// side's first point), then the two top corners.
struct Tab {
  int edge = -1;  ///< index into the edge list the tab was placed for
  EdgeSide side;  ///< the face side it hangs from
  std::array<Vec2, 4> corners;
};

/// Faces that print as a piece of their own and only just fit a sheet (print/fit.h,
/// FitPieces::large): a tab hangs from one only where none fits on the other side of its edge,
/// and only when the face with its tabs still fits `room` (layout units, at some turn).
struct LargeFaces {
  std::vector<char> face;  ///< 1 for each such face; empty: none
  Vec2 room;

  bool operator()(int f) const { return !face.empty() && face[f]; }
};

struct TabOptions {
  double height = 6;        ///< tallest tab, in layout units
  double angle_deg = 45;    ///< slant of the tab's sides against the edge
  double min_height = 2;    ///< lowest tab worth printing (half the edge on shorter edges)
  double tolerance = 1e-6;  ///< penetration depth below which polygons only touch
  LargeFaces large;
  /// Face sides (3 x face + k) whose tab is wanted there when it can be: a side whose face is too
  /// thin for its edge's label, which can print on the tab instead (print/layout.cpp). Empty:
  /// none.
  std::vector<char> prefer;
  /// The lowest tab of a preferred side that is kept there although the other side has room for
  /// a larger one (0.6 of it is the label's size on the tab: 1.5 mm).
  double prefer_min_height = 2.5;
};

/// Result of placing tabs: at most one per interior cut edge.
struct TabPlacement {
  std::vector<Tab> tabs;
  std::vector<int> omitted;  ///< edges that got no tab because none fitted on either side
};

/// Places at most one tab per interior cut edge (edges with cut_index >= 0), on side a or side b,
/// so that no tab's interior meets a face's interior or another tab's interior (separating-axis
/// test with `options.tolerance`). A tab is at most `height` tall and at most half its edge,
/// and at least `min_height` tall, or half its edge where that is less (an edge shorter than
/// 2 x min_height gets a tab exactly half its length tall). On each side the placer tries the
/// shapes of tab_shapes (core/tabs/tab_clearance.h): trapezoids over the whole edge and over
/// stretches of it (at least 40 % of the edge, at either end or in the middle) with each end
/// slanted by `angle_deg` or by 40 % of it, each as tall as fits (bisection on the height); the
/// side whose best tab has the larger area wins, except that a side `prefer` marks, when the
/// other is not marked, keeps its best tab when that is at least `prefer_min_height` tall (or as
/// tall as its edge allows, where that is lower). Edges where no tab of min_height fits are listed
/// as omitted (they need a glue strip, see strips.h). Faces are the net's triangles in layout
/// coordinates, counter-clockwise.
TabPlacement place_tabs(const std::vector<std::array<Vec2, 3>>& faces,
                        const std::vector<NetEdge>& edges, const TabOptions& options = {});

/// True when the interiors of two convex polygons (either orientation) overlap by more than
/// `tolerance` along every separating axis candidate.
bool convex_overlap(std::span<const Vec2> a, std::span<const Vec2> b, double tolerance);

/// Uniform hash grid over convex polygons, answering "does this polygon overlap any stored one".
/// A polygon is listed in the cells it meets (not every cell of its box: a long slanted sliver
/// would crowd the cells around it), and its box rules out most of the polygons of a cell
/// before the separating-axis test.
class PolygonGrid {
 public:
  explicit PolygonGrid(double cell);
  void add(std::span<const Vec2> poly);
  /// True when `poly` overlaps a stored polygon by more than `tolerance` (convex_overlap;
  /// `tolerance` >= 0).
  bool overlaps(std::span<const Vec2> poly, double tolerance);

 private:
  template <class F>
  void for_cells(std::span<const Vec2> poly, F&& f) const;

  double cell_;
  std::vector<std::vector<Vec2>> polys_;
  std::vector<std::array<double, 4>> boxes_;  ///< of each polygon: x0, y0, x1, y1
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
  std::vector<std::uint32_t> seen_;
  std::uint32_t stamp_ = 0;
};

}  // namespace papernet
