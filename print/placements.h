#pragma once

#include <array>
#include <vector>

#include "core/unfold/net.h"
#include "print/layout.h"
#include "print/pages.h"

namespace papernet {

/// Where one piece of a net lies on the printed pages (the net JSON's `print.placements`).
struct PiecePlacement {
  int piece = 0;
  int page = -1;  ///< 0-based page holding the whole piece; -1 when the layout is tiled
  /// Column-major 2x3 affine [a b c d e f]: the piece's net-frame point (u, v) (model units) lies
  /// at (a·u + c·v + e, b·u + d·v + f) mm, y down, from the top-left corner of page `page`, or,
  /// tiled, of the tile grid (see PageWindow). A rotation scaled by the print's scale, and a
  /// reflection (the net frame is y up).
  std::array<double, 6> transform{};
};

/// What one page of a tiled layout shows: the printable area of page `page` is the window
/// [x, x + width] x [y, y + height] mm of the tile grid's frame (y down, origin at the top-left
/// corner of the grid's first row and column), drawn at (margin, margin) on the page.
struct PageWindow {
  int page = 0;
  std::array<double, 4> window_mm{};  ///< x, y, width, height
};

struct PiecePlacements {
  std::vector<PiecePlacement> pieces;  ///< one per piece, by piece number
  std::vector<PageWindow> tiles;       ///< one per page when the layout is tiled, else empty
};

/// Where the pieces of `net` (each face's piece in `piece`, points in each piece's own frame)
/// lie on `pages`, once `layout` (laid out from `net` with its pieces moved rigidly, its faces in
/// the same order and corner order) is nested or paginated. Each transform is found from the
/// piece's largest face: its net-frame corners and the same corners as the page draws them
/// (draw_page), so it holds whatever rigid moves the layout made. Pieces without faces get the
/// zero transform.
PiecePlacements place_pieces(const Net& net, const std::vector<int>& piece,
                             const PrintLayout& layout, const PageLayout& pages);

}  // namespace papernet
