#pragma once
// Labels led away from their edges (print/label_leaders.cpp), a step of the labels' placement
// (print/labels.cpp).

#include <array>
#include <vector>

#include "print/internal/label_room.h"
#include "print/layout.h"

namespace papernet::print_detail {

/// Labels left under kLegibleLabelMm by every place at their edge (a short cut edge at a small
/// feature crowded with labels) print at that size, smallest first (docs/print.md, "Labels"):
/// beside their edge where a single legible label is in the way and moves (make_way), else
/// farther away, on their piece's faces, clear of every label and of the leaders drawn before,
/// with a leader line to their edge that runs over the piece and meets no other label and no
/// other leader. Places are tried on rings around the edge's middle, 2 to 15 mm, nearest first,
/// from the face's side round to the other, the text along the edge, level, or across the edge
/// (along a narrow strip that ends at the edge); where no place has a straight leader, the rings
/// are tried again with a leader of two lines, bent in front of the edge; where none has that
/// either, the leader is routed over the piece's faces (route_over_piece). A label that finds
/// no place keeps its size. None moves when more than kMostFarLabels (print/label_leaders.cpp)
/// are under the legible size, and none more when `clock` runs out. Returns the leaders.
std::vector<Segment> place_far_labels(const std::vector<std::array<Vec2, 3>>& faces,
                                      const PaperGrid& grid, std::vector<Label>& labels,
                                      const LabelClock& clock);

}  // namespace papernet::print_detail
