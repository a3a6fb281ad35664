#include "api/tabs.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>

namespace papernet {

bool convex_overlap(std::span<const Vec2> a, std::span<const Vec2> b, double tolerance) {
  // Separating axis theorem: the interiors are disjoint iff some edge normal of either polygon
  // separates their projections (up to the tolerance).
  auto separated_by_edges_of = [&](std::span<const Vec2> p) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec2 e = p[(i + 1) % p.size()] - p[i];
      const double len = norm(e);
      if (len == 0) continue;
      const Vec2 axis{-e.y / len, e.x / len};
      double a_lo = std::numeric_limits<double>::infinity(), a_hi = -a_lo;
      double b_lo = a_lo, b_hi = a_hi;
      for (Vec2 q : a) a_lo = std::min(a_lo, dot(q, axis)), a_hi = std::max(a_hi, dot(q, axis));
      for (Vec2 q : b) b_lo = std::min(b_lo, dot(q, axis)), b_hi = std::max(b_hi, dot(q, axis));
      if (std::min(a_hi, b_hi) - std::max(a_lo, b_lo) <= tolerance) return true;
    }
    return false;
  };
  return !separated_by_edges_of(a) && !separated_by_edges_of(b);
}

namespace {

/// Uniform hash grid over polygon bounding boxes; polygons have 3 or 4 corners.
class Grid {
 public:
  explicit Grid(double cell) : cell_(cell) {}

  int add(std::span<const Vec2> poly) {
    const int id = static_cast<int>(polys_.size());
    polys_.emplace_back(poly.begin(), poly.end());
    for_cells(poly, [&](std::uint64_t key) { cells_[key].push_back(id); });
    return id;
  }

  /// True when `poly` overlaps any stored polygon.
  bool overlaps(std::span<const Vec2> poly, double tolerance) {
    ++stamp_;
    seen_.resize(polys_.size(), 0);
    bool hit = false;
    for_cells(poly, [&](std::uint64_t key) {
      if (hit) return;
      const auto it = cells_.find(key);
      if (it == cells_.end()) return;
      for (int id : it->second) {
        if (seen_[id] == stamp_) continue;
        seen_[id] = stamp_;
        if (convex_overlap(poly, polys_[id], tolerance)) {
          hit = true;
          return;
        }
      }
    });
    return hit;
  }

 private:
  template <class F>
  void for_cells(std::span<const Vec2> poly, F&& f) const {
    double x0 = poly[0].x, x1 = x0, y0 = poly[0].y, y1 = y0;
    for (Vec2 p : poly)
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y),
      y1 = std::max(y1, p.y);
    const auto i0 = static_cast<std::int64_t>(std::floor(x0 / cell_));
    const auto i1 = static_cast<std::int64_t>(std::floor(x1 / cell_));
    const auto j0 = static_cast<std::int64_t>(std::floor(y0 / cell_));
    const auto j1 = static_cast<std::int64_t>(std::floor(y1 / cell_));
    for (auto i = i0; i <= i1; ++i)
      for (auto j = j0; j <= j1; ++j)
        f((static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint32_t>(j));
  }

  double cell_;
  std::vector<std::vector<Vec2>> polys_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
  std::vector<std::uint32_t> seen_;
  std::uint32_t stamp_ = 0;
};

/// The trapezoid on the outside of `side`, `height` tall with sides slanted by `angle`.
std::array<Vec2, 4> trapezoid(const std::vector<std::array<Vec2, 3>>& faces, EdgeSide side,
                              double height, double angle, double from, double to) {
  const Vec2 e0 = faces[side.face][side.k], e1 = faces[side.face][(side.k + 1) % 3];
  const double full = norm(e1 - e0);
  const Vec2 d = (1 / full) * (e1 - e0), out{d.y, -d.x};  // the face is on the left of e0->e1
  const Vec2 p0 = e0 + from * full * d, p1 = e0 + to * full * d;
  const double len = (to - from) * full;
  const double inset = std::min(height / std::tan(angle), 0.45 * len);
  return {p1, p0, p0 + height * out + inset * d, p1 + height * out - inset * d};
}

}  // namespace

/// Tab shapes tried in turn: the stretch of the edge the base covers and the slant.
struct Shape {
  double from, to;
  bool pointed;
};
constexpr Shape kShapes[] = {{0, 1, false},       {0, 1, true},        {0.2, 0.8, false},
                             {0.05, 0.55, false}, {0.45, 0.95, false}, {0.3, 0.7, true},
                             {0.05, 0.4, true},   {0.6, 0.95, true}};

TabPlacement place_tabs(const std::vector<std::array<Vec2, 3>>& faces,
                        const std::vector<NetEdge>& edges, const TabOptions& options) {
  TabPlacement result;
  if (faces.empty()) return result;
  double total = 0;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) total += norm(f[(k + 1) % 3] - f[k]);
  const double mean_edge = total / (3.0 * static_cast<double>(faces.size()));
  Grid grid(std::max(mean_edge, options.height) > 0 ? std::max(mean_edge, options.height) : 1);
  for (const auto& f : faces) grid.add(f);

  const double deg = std::numbers::pi / 180;
  const double angles[] = {options.angle_deg * deg, 0.6 * options.angle_deg * deg};
  const double scales[] = {1.0, 0.7, 0.45, 0.25};
  for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
    const NetEdge& edge = edges[e];
    if (edge.cut_index < 0) continue;
    const Vec2 p0 = faces[edge.a.face][edge.a.k], p1 = faces[edge.a.face][(edge.a.k + 1) % 3];
    const double h0 = std::min(options.height, 0.5 * norm(p1 - p0));
    bool placed = false;
    for (double s : scales) {
      for (const Shape& shape : kShapes) {
        if (placed) break;
        for (EdgeSide side : {edge.a, edge.b}) {
          if (h0 <= 0) continue;
          // Along side b the edge runs the other way: mirror the span so both sides mean the
          // same stretch of the edge.
          const bool b = side.face == edge.b.face && side.k == edge.b.k;
          const double from = b ? 1 - shape.to : shape.from, to = b ? 1 - shape.from : shape.to;
          const auto t =
              trapezoid(faces, side, s * h0 * (to - from), angles[shape.pointed], from, to);
          if (grid.overlaps(t, options.tolerance)) continue;
          grid.add(t);
          result.tabs.push_back({e, side, t});
          placed = true;
          break;
        }
        if (placed) break;
      }
      if (placed) break;
    }
    if (!placed) result.omitted.push_back(e);
  }
  return result;
}

}  // namespace papernet
