#include "print/tabs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/tabs/tab_clearance.h"
#include "core/unfold/net_metrics.h"
#include "print/fit.h"
#include "print/internal/grid_cells.h"

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

PolygonGrid::PolygonGrid(double cell) : cell_(cell > 0 && std::isfinite(cell) ? cell : 1) {}

namespace {

std::array<double, 4> box_of(std::span<const Vec2> poly) {
  std::array<double, 4> b{poly[0].x, poly[0].y, poly[0].x, poly[0].y};
  for (Vec2 p : poly)
    b = {std::min(b[0], p.x), std::min(b[1], p.y), std::max(b[2], p.x), std::max(b[3], p.y)};
  return b;
}

}  // namespace

template <class F>
void PolygonGrid::for_cells(std::span<const Vec2> poly, F&& f) const {
  const print_detail::CellRange cells = print_detail::cells_of(poly, cell_);
  // Beyond a box of 2 x 2 cells, only the cells the polygon meets (or nearly touches): two
  // polygons that overlap share one of those.
  const bool every = cells.count() <= 4;
  cells.for_each([&](std::int64_t i, std::int64_t j) {
    if (!every) {
      const double x = static_cast<double>(i) * cell_, y = static_cast<double>(j) * cell_;
      const std::array<Vec2, 4> square{Vec2{x, y}, Vec2{x + cell_, y}, Vec2{x + cell_, y + cell_},
                                       Vec2{x, y + cell_}};
      if (!convex_overlap(poly, square, -1e-9 * cell_)) return;
    }
    f(print_detail::cell_key(i, j));
  });
}

void PolygonGrid::add(std::span<const Vec2> poly) {
  const int id = static_cast<int>(polys_.size());
  polys_.emplace_back(poly.begin(), poly.end());
  boxes_.push_back(box_of(poly));
  for_cells(poly, [&](std::uint64_t key) { cells_[key].push_back(id); });
}

bool PolygonGrid::overlaps(std::span<const Vec2> poly, double tolerance) {
  ++stamp_;
  seen_.resize(polys_.size(), 0);
  const std::array<double, 4> box = box_of(poly);
  bool hit = false;
  for_cells(poly, [&](std::uint64_t key) {
    if (hit) return;
    const auto it = cells_.find(key);
    if (it == cells_.end()) return;
    for (int id : it->second) {
      if (seen_[id] == stamp_) continue;
      seen_[id] = stamp_;
      // Boxes apart: the polygons are apart, and no axis sees them overlap.
      const std::array<double, 4>& b = boxes_[id];
      if (b[0] > box[2] || box[0] > b[2] || b[1] > box[3] || box[1] > b[3]) continue;
      if (convex_overlap(poly, polys_[id], tolerance)) {
        hit = true;
        return;
      }
    }
  });
  return hit;
}

namespace {

/// The trapezoid of `shape` on the outside of `side`, `height` tall (core's tab_trapezoid, the
/// shapes the clearance pass makes room for).
std::array<Vec2, 4> trapezoid(const std::vector<std::array<Vec2, 3>>& faces, EdgeSide side,
                              const TabShape& shape, double height) {
  return tab_trapezoid(faces[side.face], side.k, shape, height);
}

/// `s` as placed on `side` of `edge`. Along side b the edge runs the other way: the span is
/// mirrored, and its ends' slants swapped, so that both sides mean the same stretch of the edge.
TabShape seen_from(const NetEdge& edge, EdgeSide side, const TabShape& s) {
  const bool on_b = side.face == edge.b.face && side.k == edge.b.k;
  return on_b ? TabShape{1 - s.to, 1 - s.from, s.tan1, s.tan0} : s;
}

double area(const std::array<Vec2, 4>& t) {
  return 0.5 * std::abs(cross(t[2] - t[0], t[3] - t[1]));
}

/// Box of a polygon, grown by `d`.
std::pair<Vec2, Vec2> bounds(std::span<const Vec2> p, double d) {
  Box2 box = Box2::empty();
  for (Vec2 q : p) box.add(q);
  return {{box.lo.x - d, box.lo.y - d}, {box.hi.x + d, box.hi.y + d}};
}

bool boxes_meet(const std::pair<Vec2, Vec2>& a, const std::pair<Vec2, Vec2>& b) {
  return a.first.x <= b.second.x && b.first.x <= a.second.x && a.first.y <= b.second.y &&
         b.first.y <= a.second.y;
}

/// Second stage of place_tabs: an edge left without a tab often has room against the faces
/// but lost it to a neighbour's tab placed first (greedily, as large as fits). For each such
/// edge, try a lowest tab (min_height) that overlaps no face and at most two tabs, and move
/// those tabs to a lowest tab elsewhere on their own edge (either side, any shape) that
/// overlaps nothing. Every tab stays checked against faces and all other tabs.
void make_room_between_tabs(const std::vector<std::array<Vec2, 3>>& faces,
                            const std::vector<NetEdge>& edges, const TabOptions& options,
                            const std::vector<TabShape>& shapes, TabPlacement& result) {
  double total = 0;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) total += norm(f[(k + 1) % 3] - f[k]);
  PolygonGrid face_grid(
      std::max(total / (3.0 * static_cast<double>(faces.size())), options.height));
  for (const auto& f : faces) face_grid.add(f);
  const auto low = [&](int e) {
    const NetEdge& edge = edges[e];
    const double len = norm(faces[edge.a.face][(edge.a.k + 1) % 3] - faces[edge.a.face][edge.a.k]);
    return std::min(options.min_height, 0.5 * len);
  };
  // Every lowest tab of edge e that overlaps no face, as (side, corners).
  const auto candidates = [&](int e) {
    std::vector<Tab> out;
    const NetEdge& edge = edges[e];
    const double h = low(e);
    if (!(h > 0)) return out;
    for (EdgeSide side : {edge.a, edge.b}) {
      if (options.large(side.face)) continue;  // its room was settled by place_tabs
      for (const TabShape& s : shapes) {
        const auto t = trapezoid(faces, side, seen_from(edge, side, s), h);
        if (!face_grid.overlaps(t, options.tolerance)) out.push_back({e, side, t});
      }
    }
    return out;
  };
  std::vector<int> still;
  for (int e : result.omitted) {
    bool done = false;
    for (const Tab& want : candidates(e)) {
      const auto box = bounds(want.corners, 0);
      std::vector<int> conflicts;
      for (int t = 0; t < static_cast<int>(result.tabs.size()) && conflicts.size() <= 2; ++t)
        if (boxes_meet(box, bounds(result.tabs[t].corners, 0)) &&
            convex_overlap(want.corners, result.tabs[t].corners, options.tolerance))
          conflicts.push_back(t);
      if (conflicts.empty() || conflicts.size() > 2) continue;
      // New places for the conflicting tabs, avoiding `want`, each other and all other tabs.
      std::vector<Tab> moved;
      for (int c : conflicts) {
        bool placed = false;
        for (const Tab& r : candidates(result.tabs[c].edge)) {
          if (convex_overlap(r.corners, want.corners, options.tolerance)) continue;
          bool free = true;
          const auto rbox = bounds(r.corners, 0);
          for (int t = 0; t < static_cast<int>(result.tabs.size()) && free; ++t)
            if (std::find(conflicts.begin(), conflicts.end(), t) == conflicts.end() &&
                boxes_meet(rbox, bounds(result.tabs[t].corners, 0)))
              free = !convex_overlap(r.corners, result.tabs[t].corners, options.tolerance);
          for (const Tab& m : moved)
            if (free) free = !convex_overlap(r.corners, m.corners, options.tolerance);
          if (free) {
            moved.push_back(r);
            placed = true;
            break;
          }
        }
        if (!placed) break;
      }
      if (moved.size() != conflicts.size()) continue;
      for (std::size_t i = 0; i < conflicts.size(); ++i) result.tabs[conflicts[i]] = moved[i];
      result.tabs.push_back(want);
      done = true;
      break;
    }
    if (!done) still.push_back(e);
  }
  result.omitted = std::move(still);
}

}  // namespace

TabPlacement place_tabs(const std::vector<std::array<Vec2, 3>>& faces,
                        const std::vector<NetEdge>& edges, const TabOptions& options) {
  TabPlacement result;
  if (faces.empty()) return result;
  double total = 0;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) total += norm(f[(k + 1) % 3] - f[k]);
  const double mean_edge = total / (3.0 * static_cast<double>(faces.size()));
  PolygonGrid grid(std::max(mean_edge, options.height));
  for (const auto& f : faces) grid.add(f);

  const std::vector<TabShape> shapes = tab_shapes(options.angle_deg);
  // A large face's corners and the tabs it carries: with one more tab it must still fit.
  std::vector<std::vector<Vec2>> large_points(options.large.face.empty() ? 0 : faces.size());
  for (std::size_t f = 0; f < large_points.size(); ++f)
    if (options.large(static_cast<int>(f)))
      large_points[f].assign(faces[f].begin(), faces[f].end());
  const auto fits_large = [&](int f, const std::array<Vec2, 4>& tab) {
    std::vector<Vec2> points = large_points[f];
    points.insert(points.end(), tab.begin(), tab.end());
    return hull_fits_turned(convex_hull(std::move(points)), options.large.room);
  };

  for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
    const NetEdge& edge = edges[e];
    if (edge.cut_index < 0) continue;
    const Vec2 p0 = faces[edge.a.face][edge.a.k], p1 = faces[edge.a.face][(edge.a.k + 1) % 3];
    const double len = norm(p1 - p0);
    if (!(len > 0)) {
      result.omitted.push_back(e);
      continue;
    }
    const double lo = std::min(options.min_height, 0.5 * len);
    const double hi = std::max(lo, std::min(options.height, 0.5 * len));
    Tab best;
    double best_area = 0, best_height = 0;
    const auto preferred = [&](EdgeSide side) {
      return side.face >= 0 && !options.prefer.empty() && options.prefer[3 * side.face + side.k];
    };
    // A large face's side last, and only when the other has no tab. Between two faces that are
    // not large, a preferred side first, where it keeps a tab tall enough (keep_first).
    const bool neither_large = !options.large(edge.a.face) && !options.large(edge.b.face);
    const bool keep_first = neither_large && preferred(edge.a) != preferred(edge.b);
    const bool a_last = (options.large(edge.a.face) && !options.large(edge.b.face)) ||
                        (keep_first && preferred(edge.b));
    for (EdgeSide side : {a_last ? edge.b : edge.a, a_last ? edge.a : edge.b}) {
      const bool large = options.large(side.face);
      if (large && best.edge >= 0) break;
      for (const TabShape& s : shapes) {
        const TabShape shape = seen_from(edge, side, s);
        // The tallest tab this shape can be bounds what it can add: skip hopeless shapes.
        if (area(trapezoid(faces, side, shape, hi)) <= best_area) continue;
        if (lo > 0 && grid.overlaps(trapezoid(faces, side, shape, lo), options.tolerance)) continue;
        double h = hi;
        if (grid.overlaps(trapezoid(faces, side, shape, hi), options.tolerance)) {
          double ok = lo, bad = hi;  // bisection: a lower tab of one shape lies inside a taller
          for (int i = 0; i < 6; ++i) {
            const double mid = 0.5 * (ok + bad);
            (grid.overlaps(trapezoid(faces, side, shape, mid), options.tolerance) ? bad : ok) = mid;
          }
          h = ok;
          if (!(h > 0)) continue;
        }
        const auto t = trapezoid(faces, side, shape, h);
        if (const double ta = area(t); ta > best_area && (!large || fits_large(side.face, t)))
          best_area = ta, best = {e, side, t}, best_height = h;
      }
      // A full-size tab over the whole edge cannot be beaten: leave side b alone. Nor can a
      // preferred side's tab as tall as it needs to be.
      if (best.edge >= 0 && best_area >= area(trapezoid(faces, side, shapes.front(), hi)) - 1e-12)
        break;
      if (keep_first && best.edge >= 0 &&
          best_height >= std::min(options.prefer_min_height, hi) - 1e-9)
        break;
    }
    if (best.edge < 0) {
      result.omitted.push_back(e);
      continue;
    }
    grid.add(best.corners);
    if (options.large(best.side.face))
      large_points[best.side.face].insert(large_points[best.side.face].end(), best.corners.begin(),
                                          best.corners.end());
    result.tabs.push_back(best);
  }
  if (!result.omitted.empty()) make_room_between_tabs(faces, edges, options, shapes, result);
  return result;
}

}  // namespace papernet
