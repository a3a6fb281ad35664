#include "print/placements.h"

#include <algorithm>
#include <cmath>

#include "print/internal/page_window.h"

namespace papernet {
namespace {

using print_detail::holds;

double area(const std::array<Vec2, 3>& t) { return 0.5 * cross(t[1] - t[0], t[2] - t[0]); }

/// The affine map that takes triangle `from` onto `to` corner by corner, column-major 2x3.
std::array<double, 6> affine(const std::array<Vec2, 3>& from, const std::array<Vec2, 3>& to) {
  const Vec2 p1 = from[1] - from[0], p2 = from[2] - from[0];
  const Vec2 q1 = to[1] - to[0], q2 = to[2] - to[0];
  const double det = cross(p1, p2);
  // [a c; b d] = [q1 q2] [p1 p2]^-1.
  const double a = (q1.x * p2.y - q2.x * p1.y) / det, c = (q2.x * p1.x - q1.x * p2.x) / det;
  const double b = (q1.y * p2.y - q2.y * p1.y) / det, d = (q2.y * p1.x - q1.y * p2.x) / det;
  return {
      a, b, c, d, to[0].x - a * from[0].x - c * from[0].y, to[0].y - b * from[0].x - d * from[0].y};
}

}  // namespace

PiecePlacements place_pieces(const Net& net, const std::vector<int>& piece,
                             const PrintLayout& layout, const PageLayout& pages) {
  int count = 0;
  for (int p : piece) count = std::max(count, p + 1);
  // Each piece's largest face: the triangle its transform is found from.
  std::vector<int> largest(static_cast<std::size_t>(count), -1);
  for (int f = 0; f < static_cast<int>(piece.size()); ++f) {
    int& best = largest[piece[f]];
    if (best < 0 || std::abs(area(net.points[f])) > std::abs(area(net.points[best]))) best = f;
  }
  PiecePlacements out;
  // Tiled: the frame of the tile grid, its top-left corner found from any page's row and column.
  Vec2 origin;
  if (!pages.fitted && !pages.pages.empty()) {
    const Page& first = pages.pages.front();
    const double step_x = pages.width - 2 * pages.margin - pages.overlap;
    const double step_y = pages.height - 2 * pages.margin - pages.overlap;
    origin = {first.lo.x - first.col * step_x, first.hi.y + first.row * step_y};
    for (int k = 0; k < static_cast<int>(pages.pages.size()); ++k) {
      const Page& page = pages.pages[k];
      out.tiles.push_back({k,
                           {page.lo.x - origin.x, origin.y - page.hi.y, page.hi.x - page.lo.x,
                            page.hi.y - page.lo.y}});
    }
  }
  for (int p = 0; p < count; ++p) {
    PiecePlacement& placed = out.pieces.emplace_back();
    placed.piece = p;
    const int f = largest[p];
    if (f < 0) continue;
    const std::array<Vec2, 3>& drawn = layout.faces[f];
    std::array<Vec2, 3> on_page;
    if (pages.fitted) {
      const Vec2 centre = (1.0 / 3) * (drawn[0] + drawn[1] + drawn[2]);
      for (int k = 0; k < static_cast<int>(pages.pages.size()) && placed.page < 0; ++k)
        if (holds(pages.pages[k], centre)) placed.page = k;
      if (placed.page < 0) continue;
      // As draw_page maps the page's window: its top-left corner at (margin, margin), y down.
      const Page& page = pages.pages[placed.page];
      for (int k = 0; k < 3; ++k)
        on_page[k] = {pages.margin + drawn[k].x - page.lo.x, pages.margin + page.hi.y - drawn[k].y};
    } else {
      for (int k = 0; k < 3; ++k) on_page[k] = {drawn[k].x - origin.x, origin.y - drawn[k].y};
    }
    placed.transform = affine(net.points[f], on_page);
  }
  return out;
}

}  // namespace papernet
