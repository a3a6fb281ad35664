// A piece's unfolding made more compact (print/internal/compact.h).
#include "print/internal/compact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

#include "core/mesh/dual_graph.h"
#include "core/unfold/net_metrics.h"
#include "core/unfold/overlap.h"
#include "core/unfold/overlap_grid.h"

namespace papernet::print_detail {

double fit_ratio(const std::vector<Vec2>& hull, Vec2 room) {
  if (hull.size() < 3) {
    double extent = 0;
    for (Vec2 p : hull)
      for (Vec2 q : hull) extent = std::max(extent, norm(p - q));
    return extent / std::max(room.x, room.y);
  }
  // Rotating calipers: along each edge of the counter-clockwise hull, the corners farthest
  // ahead, behind and away from it move on round the hull as the edges do.
  const std::size_t m = hull.size();
  const auto at = [&](std::size_t k) { return hull[k % m]; };
  double best = std::numeric_limits<double>::infinity();
  std::size_t ahead = 1, away = 1, behind = 1;
  for (std::size_t i = 0; i < m; ++i) {
    const Vec2 d = at(i + 1) - at(i);
    const double len = norm(d);
    if (!(len > 0)) continue;
    const Vec2 u = (1 / len) * d, n{-u.y, u.x};
    const Vec2 o = at(i);
    if (ahead < i + 1) ahead = i + 1;
    while (ahead < i + m && dot(at(ahead + 1) - o, u) >= dot(at(ahead) - o, u)) ++ahead;
    if (away < ahead) away = ahead;
    while (away < i + m && dot(at(away + 1) - o, n) >= dot(at(away) - o, n)) ++away;
    if (behind < away) behind = away;
    while (behind < i + m && dot(at(behind + 1) - o, u) <= dot(at(behind) - o, u)) ++behind;
    const double w = dot(at(ahead) - o, u) - std::min(0.0, dot(at(behind) - o, u));
    const double h = dot(at(away) - o, n);
    best = std::min({best, std::max(w / room.x, h / room.y), std::max(w / room.y, h / room.x)});
  }
  return best;
}

namespace {

// A branch hung elsewhere: the branch at `branch` (its faces a range of the pre-order), hung by
// its face `face` across that face's edge `edge`; `ratio` the piece's fit_ratio then.
struct Move {
  double ratio;
  int branch, face, edge;
};

}  // namespace

Compacted compact_to_fit(const Mesh& mesh, const Net& net, double scale, Vec2 room,
                         std::size_t max_evaluations, const std::function<bool()>& stop) {
  Compacted out;
  const auto n = static_cast<int>(mesh.faces.size());
  if (n < 2 || net.parent.size() != mesh.faces.size() || !(scale > 0)) return out;
  const DualGraph graph = build_dual_graph(mesh);
  const double tolerance = kOverlapTolerance * bounding_box_diagonal(mesh);
  const Vec2 room_units = (1 / scale) * room;
  std::vector<int> parent = net.parent;
  std::vector<Triangle2> pos = net.points;
  double edge_sum = 0;
  for (const Triangle2& t : pos) edge_sum += norm(t[1] - t[0]) + norm(t[2] - t[1]);
  // The faces where they lie, updated as branches move (core's index of a net's faces, as the
  // Tabu Unfolder keeps it: cells about an edge long, sprawling nets and slivers included).
  OverlapGrid grid;
  const double cell = edge_sum / (2.0 * n);
  grid.reset(cell > 0 ? cell : 1);
  for (int f = 0; f < n; ++f) grid.insert(f, triangle_box(pos[static_cast<std::size_t>(f)]));

  std::vector<std::vector<int>> links(static_cast<std::size_t>(n));
  std::vector<int> order, par(static_cast<std::size_t>(n)), size(static_cast<std::size_t>(n)),
      tin(static_cast<std::size_t>(n));
  std::vector<char> on_hull(static_cast<std::size_t>(n)), chosen(static_cast<std::size_t>(n));
  std::vector<Vec2> corners;
  // Hulls of the faces in pre-order before i (before[i]) and from i on (after[i]), and of each
  // face's branch (below[f]).
  std::vector<std::vector<Vec2>> before(static_cast<std::size_t>(n) + 1),
      after(static_cast<std::size_t>(n) + 1), below(static_cast<std::size_t>(n));
  const auto grown = [&](const std::vector<Vec2>& hull, const Triangle2& t) {
    std::vector<Vec2> points = hull;
    points.insert(points.end(), t.begin(), t.end());
    return convex_hull(std::move(points));
  };
  while (out.evaluations < max_evaluations && !(stop && stop())) {
    corners.clear();
    for (const Triangle2& t : pos) corners.insert(corners.end(), t.begin(), t.end());
    const std::vector<Vec2> hull = convex_hull(corners);
    const double ratio = fit_ratio(hull, room_units);
    if (ratio <= 1) {
      out.net = Net{parent, pos};
      return out;
    }
    // The tree rooted at the face nearest the hull's middle: branches hang outwards from it.
    Vec2 middle{0, 0};
    for (Vec2 p : hull) middle = middle + (1.0 / static_cast<double>(hull.size())) * p;
    int root = 0;
    double nearest = std::numeric_limits<double>::infinity();
    for (int f = 0; f < n; ++f) {
      const Triangle2& t = pos[static_cast<std::size_t>(f)];
      const Vec2 c = (1.0 / 3) * (t[0] + t[1] + t[2]);
      if (norm(c - middle) < nearest) nearest = norm(c - middle), root = f;
      on_hull[static_cast<std::size_t>(f)] = 0;
      for (Vec2 p : t)
        if (std::find(hull.begin(), hull.end(), p) != hull.end())
          on_hull[static_cast<std::size_t>(f)] = 1;
    }
    for (auto& l : links) l.clear();
    for (int f = 0; f < n; ++f)
      if (const int p = parent[static_cast<std::size_t>(f)]; p >= 0) {
        links[static_cast<std::size_t>(f)].push_back(p);
        links[static_cast<std::size_t>(p)].push_back(f);
      }
    order.clear();
    std::vector<int> stack{root};
    par[static_cast<std::size_t>(root)] = -1;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      tin[static_cast<std::size_t>(f)] = static_cast<int>(order.size());
      order.push_back(f);
      for (int g : links[static_cast<std::size_t>(f)])
        if (g != par[static_cast<std::size_t>(f)]) {
          par[static_cast<std::size_t>(g)] = f;
          stack.push_back(g);
        }
    }
    if (static_cast<int>(order.size()) != n) return out;  // not one tree
    for (int i = n - 1; i >= 0; --i) {
      const int f = order[static_cast<std::size_t>(i)];
      size[static_cast<std::size_t>(f)] = 1;
      for (int g : links[static_cast<std::size_t>(f)])
        if (g != par[static_cast<std::size_t>(f)])
          size[static_cast<std::size_t>(f)] += size[static_cast<std::size_t>(g)];
    }
    for (int i = 0; i < n; ++i)
      before[static_cast<std::size_t>(i) + 1] =
          grown(before[static_cast<std::size_t>(i)],
                pos[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])]);
    for (int i = n - 1; i >= 0; --i) {
      const int f = order[static_cast<std::size_t>(i)];
      after[static_cast<std::size_t>(i)] =
          grown(after[static_cast<std::size_t>(i) + 1], pos[static_cast<std::size_t>(f)]);
      std::vector<Vec2> points(pos[static_cast<std::size_t>(f)].begin(),
                               pos[static_cast<std::size_t>(f)].end());
      for (int g : links[static_cast<std::size_t>(f)])
        if (g != par[static_cast<std::size_t>(f)])
          points.insert(points.end(), below[static_cast<std::size_t>(g)].begin(),
                        below[static_cast<std::size_t>(g)].end());
      below[static_cast<std::size_t>(f)] = convex_hull(std::move(points));
    }
    // Branches that hold a hull corner, at most half the piece.
    std::vector<int> branches;
    std::fill(chosen.begin(), chosen.end(), 0);
    for (int f = 0; f < n; ++f)
      if (on_hull[static_cast<std::size_t>(f)])
        for (int c = f; c != root && 2 * size[static_cast<std::size_t>(c)] <= n &&
                        !chosen[static_cast<std::size_t>(c)];
             c = par[static_cast<std::size_t>(c)]) {
          chosen[static_cast<std::size_t>(c)] = 1;
          branches.push_back(c);
        }
    const auto in_branch = [&](int c, int x) {
      return static_cast<unsigned>(tin[static_cast<std::size_t>(x)] -
                                   tin[static_cast<std::size_t>(c)]) <
             static_cast<unsigned>(size[static_cast<std::size_t>(c)]);
    };
    const auto motion = [&](int g, int k) {
      const int h = graph.neighbour[static_cast<std::size_t>(g)][static_cast<std::size_t>(k)];
      const int e = graph.neighbour_edge[static_cast<std::size_t>(g)][static_cast<std::size_t>(k)];
      const Triangle2& tg = pos[static_cast<std::size_t>(g)];
      const Triangle2& th = pos[static_cast<std::size_t>(h)];
      // g's corners k, k + 1 are h's corners e + 1, e.
      const Vec2 dg = tg[static_cast<std::size_t>((k + 1) % 3)] - tg[static_cast<std::size_t>(k)];
      const Vec2 dh = th[static_cast<std::size_t>(e)] - th[static_cast<std::size_t>((e + 1) % 3)];
      Rigid m{tg[static_cast<std::size_t>(k)], th[static_cast<std::size_t>((e + 1) % 3)],
              dot(dg, dh), cross(dg, dh)};
      const double len = std::hypot(m.c, m.s);
      m.c /= len, m.s /= len;
      return m;
    };
    std::vector<Move> moves;
    for (int c : branches) {
      const int a = tin[static_cast<std::size_t>(c)], b = a + size[static_cast<std::size_t>(c)];
      std::vector<Vec2> rest = before[static_cast<std::size_t>(a)];
      rest.insert(rest.end(), after[static_cast<std::size_t>(b)].begin(),
                  after[static_cast<std::size_t>(b)].end());
      rest = convex_hull(std::move(rest));
      if (fit_ratio(rest, room_units) >= ratio) continue;
      const std::vector<Vec2>& own = below[static_cast<std::size_t>(c)];
      for (int i = a; i < b; ++i) {
        const int g = order[static_cast<std::size_t>(i)];
        for (int k = 0; k < 3; ++k) {
          const int h = graph.neighbour[static_cast<std::size_t>(g)][static_cast<std::size_t>(k)];
          if (h < 0 || in_branch(c, h) || (g == c && h == par[static_cast<std::size_t>(c)]) ||
              out.evaluations >= max_evaluations)
            continue;
          const Rigid m = motion(g, k);
          std::vector<Vec2> both = rest;
          for (Vec2 p : own) both.push_back(m(p));
          const double r = fit_ratio(convex_hull(std::move(both)), room_units);
          ++out.evaluations;
          if (r < ratio - 1e-9) moves.push_back({r, c, g, k});
        }
      }
      if (out.evaluations >= max_evaluations) break;
    }
    std::sort(moves.begin(), moves.end(), [](const Move& x, const Move& y) {
      return std::tie(x.ratio, x.branch, x.face, x.edge) <
             std::tie(y.ratio, y.branch, y.face, y.edge);
    });
    bool moved = false;
    for (const Move& mv : moves) {
      const Rigid m = motion(mv.face, mv.edge);
      const int a = tin[static_cast<std::size_t>(mv.branch)];
      const int b = a + size[static_cast<std::size_t>(mv.branch)];
      bool overlaps = false;
      for (int i = a; i < b && !overlaps; ++i) {
        const Triangle2& t = pos[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
        const Triangle2 there{m(t[0]), m(t[1]), m(t[2])};
        grid.query(triangle_box(there), [&](int x) {
          if (!overlaps && !in_branch(mv.branch, x) &&
              triangles_overlap(there, pos[static_cast<std::size_t>(x)], tolerance))
            overlaps = true;
        });
      }
      if (overlaps) continue;
      for (int i = a; i < b; ++i) {
        const int f = order[static_cast<std::size_t>(i)];
        Triangle2& t = pos[static_cast<std::size_t>(f)];
        t = {m(t[0]), m(t[1]), m(t[2])};
        grid.remove(f);
        grid.insert(f, triangle_box(t));
      }
      // The branch hangs from `face` now: the links on its way up to the branch's first face
      // turn round.
      int from =
          graph.neighbour[static_cast<std::size_t>(mv.face)][static_cast<std::size_t>(mv.edge)];
      for (int x = mv.face; x != -1;) {
        const int up = x == mv.branch ? -1 : par[static_cast<std::size_t>(x)];
        par[static_cast<std::size_t>(x)] = from;
        from = x;
        x = up;
      }
      parent = par;
      moved = true;
      break;
    }
    if (!moved) return out;
  }
  return out;
}

}  // namespace papernet::print_detail
