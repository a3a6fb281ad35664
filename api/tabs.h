#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/folds.h"
#include "core/vec.h"

namespace papernet {

/// A glue tab: a trapezoid on the outside of one side of a cut edge. `corners` are
/// counter-clockwise: the edge's two ends (p1, p0 of the side, so the base runs along the edge)
/// then the two top corners.
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

/// Places one tab per interior cut edge (edges with cut_index >= 0), on side a or side b,
/// trying full-size tabs first and then shorter and more pointed ones, so that no tab's interior
/// meets a face's interior or another tab's interior (separating-axis test with
/// `options.tolerance`). Faces are the net's triangles in layout coordinates, counter-clockwise.
TabPlacement place_tabs(const std::vector<std::array<Vec2, 3>>& faces,
                        const std::vector<NetEdge>& edges, const TabOptions& options = {});

/// True when the interiors of two convex polygons (either orientation) overlap by more than
/// `tolerance` along every separating axis candidate.
bool convex_overlap(std::span<const Vec2> a, std::span<const Vec2> b, double tolerance);

}  // namespace papernet
