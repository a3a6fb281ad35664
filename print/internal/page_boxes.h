#pragma once
// Boxes of text on a page and the places around a point where one fits: the overview's piece
// numbers (print/overview_sheets.cpp) and the numbers on its views of the model
// (print/model_view.cpp) share them.

#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include "core/vec.h"
#include "print/tabs.h"

namespace papernet::print_detail {

/// A box on the page: x0, y0, x1, y1 (mm).
struct PageBox {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool overlaps(const PageBox& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  bool holds(const PageBox& o) const {
    return o.x0 >= x0 && o.x1 <= x1 && o.y0 >= y0 && o.y1 <= y1;
  }
  std::array<Vec2, 4> corners() const { return {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}; }
  /// True when the segment from a to b meets the box: a line has no inside, so touching counts
  /// (tolerance below 0).
  bool crosses(Vec2 a, Vec2 b) const {
    const std::array<Vec2, 2> segment{a, b};
    return convex_overlap(segment, corners(), -1e-9);
  }
};

/// The centre nearest `at` of a text box of half-size `half` inside `inside` for which
/// `free(box)` holds: `at` itself, else the first such place on rings around it (each ring a text
/// box farther out, with eight places on the first and more on each ring after), out to `rings`.
template <class Free>
std::optional<Vec2> ring_place(Vec2 at, Vec2 half, const PageBox& inside, int rings, Free free) {
  for (int r = 0; r <= rings; ++r) {
    const int places = r == 0 ? 1 : 8 * r;
    for (int k = 0; k < places; ++k) {
      const double a = k * 2 * std::numbers::pi / places;
      const Vec2 c{at.x + r * 2 * half.x * std::cos(a), at.y + r * 2 * half.y * std::sin(a)};
      const PageBox box{c.x - half.x, c.y - half.y, c.x + half.x, c.y + half.y};
      if (inside.holds(box) && free(box)) return c;
    }
  }
  return std::nullopt;
}

}  // namespace papernet::print_detail
