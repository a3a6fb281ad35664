#pragma once
// Where each piece's number prints (print/labels.cpp, place_labels's last step).

#include <array>
#include <vector>

#include "print/layout.h"

namespace papernet::print_detail {

/// Each piece's number ("P3": piece_name), inside a face of the piece, clear of the piece's
/// edge labels and leader lines at any turn, as large as a place holds up to 8 mm: the centres of
/// the faces' inscribed circles and points towards their corners and sides are tried, in the 40
/// faces with the largest circles. Where none holds kLegibleLabelMm, that size at the place
/// farthest from the edge labels. Level (angle 0: it stays level on the page, however the piece is
/// turned). One label per
/// piece, by piece number; `faces` and `labels` as in PrintLayout (mm), `piece` each face's
/// piece.
std::vector<Label> place_piece_labels(const std::vector<std::array<Vec2, 3>>& faces,
                                      const std::vector<Label>& labels,
                                      const std::vector<Segment>& leaders,
                                      const std::vector<int>& piece);

}  // namespace papernet::print_detail
