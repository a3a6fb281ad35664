#include "print/fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <queue>
#include <utility>

#include "core/errors.h"
#include "core/unfold/net_metrics.h"
#include "core/union_find.h"

namespace papernet {
namespace {

// Width and height of the hull's box along its edge from hull[i] to hull[i + 1].
Vec2 box_along(const std::vector<Vec2>& hull, std::size_t i) {
  const Vec2 d = hull[(i + 1) % hull.size()] - hull[i];
  const double len = norm(d);
  if (!(len > 0)) return {0, 0};
  const Vec2 u = (1 / len) * d, n{-u.y, u.x};
  double lo_u = 0, hi_u = 0, lo_n = 0, hi_n = 0;
  for (std::size_t k = 0; k < hull.size(); ++k) {
    const Vec2 p = hull[k] - hull[i];
    const double a = dot(p, u), b = dot(p, n);
    lo_u = std::min(lo_u, a), hi_u = std::max(hi_u, a);
    lo_n = std::min(lo_n, b), hi_n = std::max(hi_n, b);
  }
  return {hi_u - lo_u, hi_n - lo_n};
}

// Width and height of the box of `hull` turned by `angle`.
Vec2 box_turned(const std::vector<Vec2>& hull, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  double lo_x = std::numeric_limits<double>::infinity(), hi_x = -lo_x, lo_y = lo_x, hi_y = -lo_x;
  for (Vec2 p : hull) {
    const double x = c * p.x - s * p.y, y = s * p.x + c * p.y;
    lo_x = std::min(lo_x, x), hi_x = std::max(hi_x, x);
    lo_y = std::min(lo_y, y), hi_y = std::max(hi_y, y);
  }
  return {hi_x - lo_x, hi_y - lo_y};
}

// The turns hull_fits_turned tries besides the hull's edges: every quarter degree of a quarter
// turn (the box of the next quarter turn is the same box, the other way round).
constexpr int kQuarterDegrees = 360;

double growth_in(Vec2 box, Vec2 room) {
  if (!(box.x > 0 && box.y > 0)) return 0;
  return std::max(std::min(room.x / box.x, room.y / box.y),
                  std::min(room.y / box.x, room.x / box.y));
}

/// The largest factor by which the hull can grow and still fit `room` along one of its edges, as
/// hull_fits asks.
double growth_along_edges(const std::vector<Vec2>& hull, Vec2 room) {
  double best = 0;
  for (std::size_t i = 0; i < hull.size(); ++i)
    best = std::max(best, growth_in(box_along(hull, i), room));
  return best;
}

/// The largest factor by which the hull can grow and still fit `room` at some turn of
/// hull_fits_turned.
double growth_that_fits(const std::vector<Vec2>& hull, Vec2 room) {
  double best = growth_along_edges(hull, room);
  for (int q = 0; q < kQuarterDegrees; ++q)
    best = std::max(
        best, growth_in(box_turned(hull, q * std::numbers::pi / (2 * kQuarterDegrees)), room));
  return best;
}

}  // namespace

double largest_size_joining_faces(const Net& net, double scale, Vec2 room, double model_mm) {
  double growth = 0;
  for (std::size_t f = 0; f < net.parent.size(); ++f) {
    const int p = net.parent[f];
    if (p < 0) continue;
    std::vector<Vec2> corners;
    for (Vec2 c : net.points[f]) corners.push_back(scale * c);
    for (Vec2 c : net.points[static_cast<std::size_t>(p)]) corners.push_back(scale * c);
    growth = std::max(growth, growth_along_edges(convex_hull(std::move(corners)), room));
  }
  return growth * model_mm;
}

bool hull_fits(const std::vector<Vec2>& hull, Vec2 room) {
  if (hull.size() < 3) {
    double extent = 0;
    for (Vec2 p : hull)
      for (Vec2 q : hull) extent = std::max(extent, norm(p - q));
    return extent <= std::max(room.x, room.y);
  }
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec2 b = box_along(hull, i);
    if ((b.x <= room.x && b.y <= room.y) || (b.x <= room.y && b.y <= room.x)) return true;
  }
  return false;
}

bool hull_fits_turned(const std::vector<Vec2>& hull, Vec2 room) {
  if (hull_fits(hull, room)) return true;
  if (hull.size() < 3) return false;
  for (int q = 1; q < kQuarterDegrees; ++q) {
    const Vec2 b = box_turned(hull, q * std::numbers::pi / (2 * kQuarterDegrees));
    if ((b.x <= room.x && b.y <= room.y) || (b.x <= room.y && b.y <= room.x)) return true;
  }
  return false;
}

double hull_area(const std::vector<Vec2>& hull) {
  double a = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) a += cross(hull[i], hull[(i + 1) % hull.size()]);
  return 0.5 * std::abs(a);
}

namespace {

std::string mm(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f", v);
  return buf;
}

// Glues cut links back where the two pieces they join fit `target` together, the smallest such
// joined piece (by hull area) first, until none is left: cutting the largest subtrees first
// from the leaves up can cut one whose remainder would have fitted with it after the next cut,
// and leave a small remainder that its parent cuts off again. `order` lists parents before
// children; `cut[f]` says f's link to its parent is cut. A face `large` marks stays alone.
void glue_back(const Net& net, const std::vector<int>& order,
               const std::vector<std::vector<Vec2>>& face_hull, const std::vector<char>& large,
               Vec2 target, std::vector<char>& cut) {
  const auto n = static_cast<int>(net.parent.size());
  std::vector<int> root(n);
  for (int f : order) root[f] = cut[f] || net.parent[f] < 0 ? f : root[net.parent[f]];
  std::vector<std::vector<Vec2>> hull(n);  // of each piece, at its root
  {
    std::vector<std::vector<Vec2>> pts(n);
    for (int f = 0; f < n; ++f)
      pts[root[f]].insert(pts[root[f]].end(), face_hull[f].begin(), face_hull[f].end());
    for (int f = 0; f < n; ++f)
      if (root[f] == f) hull[f] = convex_hull(std::move(pts[f]));
  }
  UnionFind pieces(static_cast<std::size_t>(n));
  // Each piece's stamp, at its representative, new when it grows; a candidate is the joined
  // piece of a link, with the stamps of its two pieces when it was made. Pieces only grow, so a
  // link whose pieces do not fit together never will, and a stale candidate's area is at most
  // the link's now: popped, it is made again, and the smallest is still taken first.
  std::vector<int> stamp(n, 0);
  int stamps = 0;
  struct Candidate {
    double area;
    int link, stamp_a, stamp_b;
    bool operator>(const Candidate& o) const {
      return std::pair{area, link} > std::pair{o.area, o.link};
    }
  };
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> queue;
  std::vector<std::vector<Vec2>> joined(n);  // the hull of each candidate in the queue
  const auto consider = [&](int c) {
    const int a = pieces.find(root[c]), b = pieces.find(root[net.parent[c]]);
    std::vector<Vec2> pts = hull[a];
    pts.insert(pts.end(), hull[b].begin(), hull[b].end());
    std::vector<Vec2> h = convex_hull(std::move(pts));
    if (!hull_fits_turned(h, target)) return;
    queue.push({hull_area(h), c, stamp[a], stamp[b]});
    joined[c] = std::move(h);
  };
  for (int f : order)
    if (cut[f] && !large[f] && !large[net.parent[f]]) consider(f);
  while (!queue.empty()) {
    const Candidate top = queue.top();
    queue.pop();
    const int c = top.link;
    const int a = pieces.find(root[c]), b = pieces.find(root[net.parent[c]]);
    if (stamp[a] != top.stamp_a || stamp[b] != top.stamp_b) {
      consider(c);
      continue;
    }
    cut[c] = 0;
    pieces.unite(a, b);
    const int joint = pieces.find(a);
    hull[joint] = std::move(joined[c]);
    stamp[joint] = ++stamps;
  }
}

}  // namespace

FitPieces cut_to_fit(const Net& net, const std::vector<int>& piece, double scale, FitRoom fit,
                     const std::string& paper_name, double model_mm, double shrink, double glue) {
  const auto n = static_cast<int>(net.parent.size());
  const Vec2 room = fit.room;
  const Vec2 alone = fit.alone.x > 0 && fit.alone.y > 0 ? fit.alone : fit.room;
  FitPieces out{net, piece, 0, 0, std::vector<char>(n, 0)};
  for (int p : piece) out.pieces = std::max(out.pieces, p + 1);
  std::vector<std::vector<Vec2>> face_hull(n);
  int too_large = -1;
  for (int f = 0; f < n; ++f) {
    std::vector<Vec2> pts;
    for (Vec2 p : net.points[f]) pts.push_back(scale * p);
    face_hull[f] = convex_hull(pts);
    // A face larger than the room with tabs prints alone, turned as it fits the sheet.
    const bool large = !hull_fits(face_hull[f], room);
    out.large[f] = large;
    if (too_large < 0 && large && !hull_fits_turned(face_hull[f], alone)) too_large = f;
  }
  if (too_large >= 0) {
    // The largest model that prints: every face fits `alone` at some turn.
    double growth = std::numeric_limits<double>::infinity();
    for (int f = 0; f < n; ++f)
      if (const double g = growth_that_fits(face_hull[f], alone); g > 0)  // 0: no area
        growth = std::min(growth, g);
    const OrientedBox box = min_area_box(face_hull[too_large]);
    throw InvalidOptionException(
        "face_too_large", "size_mm",
        "face " + std::to_string(too_large) + " prints " + mm(std::max(box.width(), box.height())) +
            " x " + mm(std::min(box.width(), box.height())) + " mm, larger than " + paper_name +
            " paper holds (" + mm(std::max(alone.x, alone.y)) + " x " +
            mm(std::min(alone.x, alone.y)) + " mm with margins, at any turn): at most " +
            mm(std::floor(model_mm * growth)) + " mm (size_mm) prints on " + paper_name +
            ", or choose larger paper");
  }
  std::vector<std::vector<int>> children(n);
  std::vector<int> order;  // roots first, then breadth-first: parents before children
  for (int f = 0; f < n; ++f) {
    if (net.parent[f] >= 0)
      children[net.parent[f]].push_back(f);
    else
      order.push_back(f);
  }
  for (std::size_t i = 0; i < order.size(); ++i)
    for (int c : children[order[i]]) order.push_back(c);

  const Vec2 target = std::clamp(shrink, 0.0, 1.0) * room;
  // hull[f]: the convex hull (mm) of what remains of f's subtree after the cuts below it.
  std::vector<std::vector<Vec2>> hull(n);
  std::vector<char> cut(n, 0);
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const int f = *it;
    const std::vector<Vec2>& own = face_hull[f];
    std::vector<int> kept = children[f];
    // Largest first: cutting off the largest subtree frees the most room.
    std::sort(kept.begin(), kept.end(),
              [&](int a, int b) { return hull_area(hull[a]) < hull_area(hull[b]); });
    for (;;) {
      std::vector<Vec2> pts = own;
      for (int c : kept) pts.insert(pts.end(), hull[c].begin(), hull[c].end());
      std::vector<Vec2> h = convex_hull(pts);
      if (hull_fits(h, target) || kept.empty()) {
        hull[f] = std::move(h);
        break;
      }
      cut[kept.back()] = 1;
      kept.pop_back();
    }
  }
  glue_back(net, order, face_hull, out.large, std::clamp(std::max(shrink, glue), 0.0, 1.0) * room,
            cut);
  // The cut subtrees become pieces, numbered after the input's.
  for (int f : order) {
    if (!cut[f]) {
      if (out.net.parent[f] >= 0) out.piece[f] = out.piece[out.net.parent[f]];
      continue;
    }
    out.net.parent[f] = -1;
    out.piece[f] = out.pieces++;
    ++out.cut_links;
  }
  return out;
}

}  // namespace papernet
