#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/folds.h"
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

struct TabOptions {
  double height = 6;      ///< tallest tab, in layout units; never more than half the edge's length
  double angle_deg = 45;  ///< slant of the tab's sides against the edge
  double tolerance = 1e-6;  ///< penetration depth below which polygons only touch
};

/// Result of placing tabs: at most one per interior cut edge.
struct TabPlacement {
  std::vector<Tab> tabs;
  std::vector<int> omitted;  ///< edges that got no tab because none fitted on either side
};

/// Places one tab per interior cut edge (edges with cut_index >= 0), on side a or side b, so
/// that no tab's interior meets a face's interior or another tab's interior (separating-axis
/// test with `options.tolerance`). For each height (full, then 70, 45, 25 %) it tries shapes in
/// turn on both sides: the whole edge, the whole edge with steeper slants, then bases on part of
/// the edge (the middle, either end), which fit into wedge-shaped gaps of the net. Edges where
/// nothing fits are listed as omitted. Faces are the net's triangles in layout coordinates,
/// counter-clockwise.
TabPlacement place_tabs(const std::vector<std::array<Vec2, 3>>& faces,
                        const std::vector<NetEdge>& edges, const TabOptions& options = {});

/// True when the interiors of two convex polygons (either orientation) overlap by more than
/// `tolerance` along every separating axis candidate.
bool convex_overlap(std::span<const Vec2> a, std::span<const Vec2> b, double tolerance);

}  // namespace papernet
