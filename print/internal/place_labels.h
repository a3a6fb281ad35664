#pragma once
// The labels of a laid-out net (print/labels.cpp), the last step of layout_net
// (print/layout.cpp), which also sizes the labels it weighs for the glue tabs.

#include <array>
#include <string>
#include <vector>

#include "print/layout.h"

namespace papernet::print_detail {

/// The text of cut edge `number`'s labels: "6" and "9" (and "16" and "91", ...) read as each
/// other upside down, so those end in a dot.
std::string label_text(int number);

/// Numbers the cut edges of a laid-out net (their `cut_index`, the number printed minus one) so
/// that the shortest edge, whose label has the least room, prints the narrowest number: the
/// edges from the shortest (ties in order of the edges), the numbers 1 to N from the narrowest
/// text (label_text: one digit before two, a number that needs no dot before one that does;
/// ties in order) (docs/print.md, "Labels").
void number_cut_edges(const std::vector<std::array<Vec2, 3>>& faces, std::vector<NetEdge>& edges);

/// The label for `side`, sized to fit the face: text along the edge, inside the triangle, at
/// most `max_size` tall, turned to read upright on the page.
Label make_label(const std::array<Vec2, 3>& tri, EdgeSide side, std::string text, double max_size);

/// Places the labels of a laid-out net (`out`, before it is moved to the origin): their sizes and
/// places, the leaders of those placed away from their edges, and each piece's number
/// (docs/print.md, "Labels"). `tab_of`: each edge's tab in `out.tabs`, or -1; `piece`: each
/// face's piece (empty: one), `pieces` how many.
void place_labels(PrintLayout& out, const std::vector<int>& tab_of, const std::vector<int>& piece,
                  int pieces, const PrintOptions& options);

}  // namespace papernet::print_detail
