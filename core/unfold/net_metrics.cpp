#include "core/unfold/net_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace papernet {

Vec2 rotate(Vec2 p, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * p.x - s * p.y, s * p.x + c * p.y};
}

std::vector<Vec2> convex_hull(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(),
            [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Vec2> hull(2 * points.size());
  std::size_t k = 0;
  auto turn = [&](Vec2 p) { return cross(hull[k - 1] - hull[k - 2], p - hull[k - 2]); };
  for (const Vec2& p : points) {  // lower chain
    while (k >= 2 && turn(p) <= 0) --k;
    hull[k++] = p;
  }
  const std::size_t lower = k + 1;
  for (auto it = points.rbegin() + 1; it != points.rend(); ++it) {  // upper chain
    while (k >= lower && turn(*it) <= 0) --k;
    hull[k++] = *it;
  }
  hull.resize(k - 1);
  return hull;
}

OrientedBox min_area_box(const std::vector<Vec2>& points) {
  OrientedBox best;
  const std::vector<Vec2> hull = convex_hull(points);
  const std::size_t n = hull.size();
  if (n == 0) return best;
  if (n < 3) {  // a point or a segment: align the segment with x
    const Vec2 d = hull.back() - hull.front();
    best.angle = n == 2 ? -std::atan2(d.y, d.x) : 0;
    const Vec2 p = rotate(hull.front(), best.angle), q = rotate(hull.back(), best.angle);
    best.lo = {std::min(p.x, q.x), std::min(p.y, q.y)};
    best.hi = {std::max(p.x, q.x), std::max(p.y, q.y)};
    return best;
  }
  // Rotating calipers: for hull edge i (direction u, inward normal v = left of u) keep the
  // indices of the points extreme along u (max), -u (min) and v (max); each only advances.
  double best_area = std::numeric_limits<double>::infinity();
  std::size_t right = 0, top = 0, left = 0;
  auto at = [&](std::size_t i) { return hull[i % n]; };
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 o = hull[i], e = at(i + 1) - o;
    const double len = norm(e);
    if (len == 0) continue;
    const Vec2 u = (1 / len) * e, v{-u.y, u.x};
    auto advance = [&](std::size_t& k, Vec2 dir, double sign) {
      while (k + 1 <= i + n && sign * dot(at(k + 1) - o, dir) >= sign * dot(at(k) - o, dir)) ++k;
    };
    right = std::max(right, i + 1);
    advance(right, u, 1);
    top = std::max(top, right);
    advance(top, v, 1);
    left = std::max(left, top);
    advance(left, u, -1);
    const double x_max = dot(at(right) - o, u), x_min = dot(at(left) - o, u);
    const double y_max = dot(at(top) - o, v);
    const double area = (x_max - x_min) * y_max;
    if (area < best_area) {
      best_area = area;
      // Rotate so that u maps to +x; v then maps to +y.
      best.angle = -std::atan2(u.y, u.x);
      const Vec2 ro = rotate(o, best.angle);
      best.lo = {ro.x + x_min, ro.y};
      best.hi = {ro.x + x_max, ro.y + y_max};
    }
  }
  if (best.height() > best.width()) {  // put the long side along x
    best.angle += std::numbers::pi / 2;
    const Vec2 lo = best.lo, hi = best.hi;
    best.lo = {-hi.y, lo.x};
    best.hi = {-lo.y, hi.x};
  }
  return best;
}

NetBoxMetrics net_metrics(const Mesh& mesh, const Net& net) {
  NetBoxMetrics m;
  m.faces = static_cast<int>(mesh.faces.size());
  std::vector<Vec2> points;
  points.reserve(3 * net.points.size());
  for (const auto& tri : net.points) points.insert(points.end(), tri.begin(), tri.end());
  for (int f = 0; f < m.faces; ++f) m.face_area += face_area(mesh, f);
  m.box = min_area_box(points);
  const double area = m.box.area();
  if (area > 0) m.coverage = m.face_area / area;
  if (m.box.height() > 0) m.aspect_ratio = m.box.width() / m.box.height();
  return m;
}

}  // namespace papernet
