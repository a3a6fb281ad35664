#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/vec.h"

namespace papernet {

using Triangle2 = std::array<Vec2, 3>;

/// Axis-aligned box in the plane.
struct Box2 {
  Vec2 lo, hi;
};

inline Box2 triangle_box(const Triangle2& t) {
  return {{std::min({t[0].x, t[1].x, t[2].x}), std::min({t[0].y, t[1].y, t[2].y})},
          {std::max({t[0].x, t[1].x, t[2].x}), std::max({t[0].y, t[1].y, t[2].y})}};
}

/// True when the interiors of the counter-clockwise triangles a and b intersect by more than
/// `tolerance` (a length; use a small fraction of the mesh's size, e.g. 1e-9 of its bounding-box
/// diagonal). Triangles that touch along an edge or at a vertex, or whose shared corners differ
/// by rounding, do not overlap. Exact for glued neighbours: a shared edge copied bit for bit
/// separates them even with tolerance 0. Uses separating axes along the six edges, which is
/// exact for convex polygons in the plane.
bool triangles_overlap(const Triangle2& a, const Triangle2& b, double tolerance);

/// Uniform hash grid over face boxes, updated incrementally: the spatial index of a net.
/// Cells hash into a power-of-two table of buckets without keys (cells that collide share a
/// bucket, which only adds candidates), so a query is a few array lookups. Faces much larger
/// than a cell are kept in a short list that every query returns.
class OverlapGrid {
 public:
  /// Empties the grid and sets its cell size (> 0), typically about an average edge length.
  void reset(double cell_size);
  /// Inserts face f (not in the grid) with box `box`.
  void insert(int f, const Box2& box);
  /// Removes face f (in the grid).
  void remove(int f);
  bool contains(int f) const { return f < static_cast<int>(range_.size()) && range_[f].valid; }
  /// Calls visit(face) for every face whose cells meet `box`; a face may be visited more than
  /// once, and faces whose boxes do not meet `box` may be visited too.
  template <class Visit>
  void query(const Box2& box, Visit&& visit) const;

 private:
  struct Range {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
    bool valid = false, big = false;
  };
  std::size_t bucket(int x, int y) const {
    const std::uint64_t h = static_cast<std::uint32_t>(x) * 0x9e3779b1u ^
                            static_cast<std::uint64_t>(static_cast<std::uint32_t>(y)) * 0x85ebca6bu;
    return static_cast<std::size_t>((h ^ (h >> 15)) & mask_);
  }
  int cell(double v) const { return static_cast<int>(std::floor(v * inv_cell_)); }
  void place(int f);
  void grow();

  double inv_cell_ = 1;
  std::size_t mask_ = 0, count_ = 0;
  std::vector<std::vector<int>> buckets_;
  std::vector<Range> range_;
  std::vector<int> big_;
};

template <class Visit>
void OverlapGrid::query(const Box2& box, Visit&& visit) const {
  for (int f : big_) visit(f);
  const int x0 = cell(box.lo.x), x1 = cell(box.hi.x), y0 = cell(box.lo.y), y1 = cell(box.hi.y);
  for (int x = x0; x <= x1; ++x)
    for (int y = y0; y <= y1; ++y)
      for (int f : buckets_[bucket(x, y)]) visit(f);
}

}  // namespace papernet
