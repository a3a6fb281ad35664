#pragma once
// A piece's unfolding made more compact by hanging its branches elsewhere, until it fits a room
// (print/merge.cpp's pairs; docs/print.md, "Fit layout").

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/unfold/net.h"
#include "core/vec.h"

namespace papernet::print_detail {

/// How far the convex polygon `hull` (counter-clockwise, as core/unfold/net_metrics.h's
/// convex_hull makes it) is from fitting a `room` box: of the boxes along its edges, either way
/// round, the least ratio of a box's side to the room's side it lies along (the larger of its
/// two). At most 1 where print/fit.h's hull_fits says it fits. Linear in the hull's corners
/// (rotating calipers).
double fit_ratio(const std::vector<Vec2>& hull, Vec2 room);

struct Compacted {
  std::optional<Net> net;       ///< the net that fits; none when no way was found
  std::size_t evaluations = 0;  ///< branches hung elsewhere and measured
};

/// `net`, an overlap-free unfolding of `mesh` in one piece (at `scale` millimetres per unit), made
/// to fit a `room` box (fit_ratio at most 1) by moving whole branches: a branch of the unfold tree
/// (rooted at the face nearest the middle of the piece's hull) that holds a corner of the hull and
/// at most half the faces is cut from the face it hangs from and hung across another of its edges
/// to the rest of the piece, where it lies flat without overlap (core/unfold/overlap.h's test and
/// tolerance), the move that leaves the piece nearest to fitting first, until it fits or no move
/// brings it nearer. Each face keeps its shape; the unfold tree stays one tree. At most
/// `max_evaluations` moves are measured, and none once `stop` says so (then no net; `stop` may
/// instead throw, as a cancelled job's CancelledException, which then passes through).
Compacted compact_to_fit(const Mesh& mesh, const Net& net, double scale, Vec2 room,
                         std::size_t max_evaluations, const std::function<bool()>& stop = {});

}  // namespace papernet::print_detail
