#pragma once
// The cells of a uniform grid that a shape's bounding box covers: the hash grids of the print
// (labels and cut lines in print/label_room.cpp, faces and tabs in print/tabs.cpp) share them.

#include <cmath>
#include <cstdint>
#include <span>

#include "core/vec.h"

namespace papernet::print_detail {

/// The key of grid cell (x, y) in a hash map of cells.
inline std::uint64_t cell_key(std::int64_t x, std::int64_t y) {
  return static_cast<std::uint64_t>(x) << 32 ^ static_cast<std::uint32_t>(y);
}

/// The cell that coordinate `v` falls in, for cells of side `cell`.
inline std::int64_t cell_of(double v, double cell) {
  return static_cast<std::int64_t>(std::floor(v / cell));
}

/// The cells, of side `cell`, of the bounding box of `points`: columns x0..x1, rows y0..y1.
struct CellRange {
  std::int64_t x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  std::int64_t count() const { return (x1 - x0 + 1) * (y1 - y0 + 1); }
  /// Calls f(x, y) for each cell of the range, row by row.
  template <class F>
  void for_each(F&& f) const {
    for (std::int64_t y = y0; y <= y1; ++y)
      for (std::int64_t x = x0; x <= x1; ++x) f(x, y);
  }
};

inline CellRange cells_of(std::span<const Vec2> points, double cell) {
  if (points.empty()) return {};
  Box2 b = Box2::empty();
  for (const Vec2 p : points) b.add(p);
  return {cell_of(b.lo.x, cell), cell_of(b.lo.y, cell), cell_of(b.hi.x, cell),
          cell_of(b.hi.y, cell)};
}

/// The key of the cell, of side `cell`, that `p` falls in.
inline std::uint64_t cell_key_of(Vec2 p, double cell) {
  return cell_key(cell_of(p.x, cell), cell_of(p.y, cell));
}

/// Calls f(key) with the key of each cell, of side `cell`, of the bounding box of `points`.
template <class F>
void for_each_cell_key(std::span<const Vec2> points, double cell, F&& f) {
  cells_of(points, cell).for_each([&](std::int64_t x, std::int64_t y) { f(cell_key(x, y)); });
}

}  // namespace papernet::print_detail
