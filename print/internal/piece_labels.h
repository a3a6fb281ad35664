#pragma once
// Where each piece's number prints (print/layout.cpp, layout_net's last step).

#include <array>
#include <vector>

#include "print/layout.h"

namespace papernet::print_detail {

/// Each piece's number ("P3": piece_name), inside the face of the piece with the largest
/// inscribed circle that holds it clear of the piece's edge labels at any turn, as large as
/// that circle holds up to 8 mm (at least 3 mm where any face allows; else kLegibleLabelMm),
/// level (angle 0: it stays level on the page, however the piece is turned). One label per
/// piece, by piece number; `faces` and `labels` as in PrintLayout (mm), `piece` each face's
/// piece.
std::vector<Label> place_piece_labels(const std::vector<std::array<Vec2, 3>>& faces,
                                      const std::vector<Label>& labels,
                                      const std::vector<int>& piece);

}  // namespace papernet::print_detail
