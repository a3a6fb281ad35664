#pragma once
// Convex-polygon geometry for the print tests, written apart from the print code so that its
// checks are independent of the tab placer's and the nester's own tests.

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/vec.h"

namespace papernet::test {

/// Distance from `p` to the segment from `a` to `b`.
inline double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const double len2 = dot(b - a, b - a);
  const double t = len2 > 0 ? std::clamp(dot(p - a, b - a) / len2, 0.0, 1.0) : 0;
  return norm(p - (a + t * (b - a)));
}

inline double signed_area(const std::vector<Vec2>& p) {
  double a = 0;  // relative to p[0]: absolute coordinates would drown tiny areas in rounding
  for (std::size_t i = 1; i + 1 < p.size(); ++i) a += cross(p[i] - p[0], p[i + 1] - p[0]);
  return 0.5 * a;
}

/// Intersection of two convex polygons (Sutherland-Hodgman clipping).
inline std::vector<Vec2> intersection(std::vector<Vec2> subject, std::vector<Vec2> clip) {
  if (signed_area(clip) < 0) std::reverse(clip.begin(), clip.end());
  for (std::size_t i = 0; i < clip.size() && !subject.empty(); ++i) {
    const Vec2 a = clip[i], b = clip[(i + 1) % clip.size()];
    auto inside = [&](Vec2 p) { return cross(b - a, p - a) >= 0; };
    std::vector<Vec2> out;
    for (std::size_t j = 0; j < subject.size(); ++j) {
      const Vec2 p = subject[j], q = subject[(j + 1) % subject.size()];
      const bool ip = inside(p), iq = inside(q);
      if (ip) out.push_back(p);
      if (ip != iq) {
        const double t = cross(b - a, p - a) / (cross(b - a, p - a) - cross(b - a, q - a));
        out.push_back(p + t * (q - p));
      }
    }
    subject = std::move(out);
  }
  return subject;
}

/// True when the bounding boxes of two polygons are apart by more than `gap`.
inline bool boxes_apart(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double gap) {
  auto box = [](const std::vector<Vec2>& p) {
    Vec2 lo = p[0], hi = p[0];
    for (Vec2 q : p)
      lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)},
      hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
    return std::pair{lo, hi};
  };
  const auto [alo, ahi] = box(a);
  const auto [blo, bhi] = box(b);
  return alo.x > bhi.x + gap || blo.x > ahi.x + gap || alo.y > bhi.y + gap || blo.y > ahi.y + gap;
}

inline double intersection_area(std::vector<Vec2> a, std::vector<Vec2> b) {
  const auto p = intersection(std::move(a), std::move(b));
  return p.size() < 3 ? 0 : std::abs(signed_area(p));
}

/// Mean thickness of the intersection of two convex polygons (area / longest extent): how deep
/// they really overlap. Shapes that only touch give 0 up to rounding.
inline double overlap_thickness(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  if (boxes_apart(a, b, 0)) return 0;
  const auto p = intersection(a, b);
  if (p.size() < 3) return 0;
  double extent = 0;
  for (Vec2 u : p)
    for (Vec2 v : p) extent = std::max(extent, norm(u - v));
  return extent > 0 ? std::abs(signed_area(p)) / extent : 0;
}

/// Calls f(i, j) for each polygon a[i] and b[j] whose bounding boxes are within `gap` of each
/// other: the only pairs that can overlap (or come within `gap`). A sweep over the boxes sorted
/// by their left side, so that checks of every pair of a large net stay fast in sanitized
/// builds.
template <class F>
void near_pairs(const std::vector<std::vector<Vec2>>& a, const std::vector<std::vector<Vec2>>& b,
                double gap, F&& f) {
  struct Box {
    Vec2 lo, hi;
  };
  auto boxes = [](const std::vector<std::vector<Vec2>>& polygons) {
    std::vector<Box> out;
    for (const auto& p : polygons) {
      Box box{p[0], p[0]};
      for (Vec2 q : p)
        box.lo = {std::min(box.lo.x, q.x), std::min(box.lo.y, q.y)},
        box.hi = {std::max(box.hi.x, q.x), std::max(box.hi.y, q.y)};
      out.push_back(box);
    }
    return out;
  };
  const std::vector<Box> ba = boxes(a), bb = boxes(b);
  std::vector<std::size_t> order(b.size());
  double widest = 0;
  for (std::size_t j = 0; j < b.size(); ++j)
    order[j] = j, widest = std::max(widest, bb[j].hi.x - bb[j].lo.x);
  std::sort(order.begin(), order.end(),
            [&](std::size_t i, std::size_t j) { return bb[i].lo.x < bb[j].lo.x; });
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Box& x = ba[i];
    // Boxes of b that can reach x start at most `widest` left of it.
    auto first = std::lower_bound(order.begin(), order.end(), x.lo.x - gap - widest,
                                  [&](std::size_t j, double v) { return bb[j].lo.x < v; });
    for (auto it = first; it != order.end() && bb[*it].lo.x <= x.hi.x + gap; ++it) {
      const Box& y = bb[*it];
      if (y.hi.x + gap < x.lo.x || y.lo.y > x.hi.y + gap || x.lo.y > y.hi.y + gap) continue;
      f(i, *it);
    }
  }
}

}  // namespace papernet::test
