// Pieces grown from single faces, flattest folds first (print/fit.h, grow_to_fit).
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <numeric>

#include "core/mesh/dual_graph.h"
#include "core/tabs/tab_clearance.h"
#include "core/unfold/folds.h"
#include "core/unfold/net_metrics.h"
#include "core/unfold/overlap.h"
#include "core/unfold/overlap_grid.h"
#include "core/unfold/unfold_tree.h"
#include "print/fit.h"

namespace papernet {
namespace {

// How much a fold's angle (over pi) weighs against gluing it: concave folds are harder to fold
// neatly than convex ones, and an edge longer than the mean is a little cheaper to keep glued
// (a shorter cut to glue). The weights of Blender's paper-model exporter.
constexpr double kConvexWeight = 0.5;
constexpr double kConcaveWeight = 1;
constexpr double kLengthWeight = -0.05;

// Pieces of more faces than this find overlap candidates through a grid of their own; smaller
// ones are scanned.
constexpr std::size_t kGridFaces = 48;

struct Grown {
  std::vector<int> faces;
  std::vector<Vec2> hull;  // of the corners, in mm
  std::unique_ptr<OverlapGrid> grid;
};

struct Join {
  double priority;
  int f, k;  // face f, its edge k
};

// The rigid motion taking the segment p0 -> p1 onto q0 -> q1 (of the same length).
Rigid motion(Vec2 p0, Vec2 p1, Vec2 q0, Vec2 q1) {
  const Vec2 a = p1 - p0, b = q1 - q0;
  const double la = norm(a), lb = norm(b);
  Rigid m{p0, q0};
  if (la > 0 && lb > 0) {
    m.c = dot(a, b) / (la * lb);
    m.s = cross(a, b) / (la * lb);
  }
  return m;
}

}  // namespace

FitPieces grow_to_fit(const Mesh& mesh, const std::vector<int>& piece, double scale, FitRoom room,
                      double tab_height, double tab_angle_deg) {
  const auto n = static_cast<int>(mesh.faces.size());
  FitPieces out;
  out.large.assign(n, 0);
  out.net.parent.assign(n, -1);
  out.net.points.resize(n);
  const DualGraph graph = build_dual_graph(mesh);
  const double tolerance = kOverlapTolerance * bounding_box_diagonal(mesh);
  const double cell = std::max(median_edge_length(mesh), 1e-12);

  std::vector<Grown> grown(n);
  std::vector<int> of(n);  // the piece each face is in, by its index in `grown`
  for (int f = 0; f < n; ++f) {
    out.net.points[f] = place_root(mesh, f, face_shape(mesh, f));
    grown[f].faces = {f};
    grown[f].hull = convex_hull({out.net.points[f].begin(), out.net.points[f].end()});
    std::vector<Vec2> mm;
    for (Vec2 p : grown[f].hull) mm.push_back(scale * p);
    out.large[f] = !hull_fits(mm, room.room);  // alone: no join fits either
    of[f] = f;
  }

  const auto edge_length = [&](int f, int k) {
    return norm(mesh.vertices[mesh.faces[f][(k + 1) % 3]] - mesh.vertices[mesh.faces[f][k]]);
  };
  std::vector<Join> joins;  // priority: the fold angle until the mean length is known
  double total_length = 0;
  for (int f = 0; f < n; ++f)
    for (int k = 0; k < 3; ++k) {
      const int g = graph.neighbour[f][k];
      if (g < f || piece[g] != piece[f]) continue;  // boundary, listed from g, or between parts
      joins.push_back({fold_angle(mesh, f, g), f, k});
      total_length += edge_length(f, k);
    }
  const double mean_length = joins.empty() ? 1 : total_length / static_cast<double>(joins.size());
  for (Join& j : joins) {
    const double angle = j.priority;
    j.priority = (angle > 0 ? kConvexWeight : -kConcaveWeight) * angle / std::numbers::pi +
                 kLengthWeight * edge_length(j.f, j.k) / mean_length;
  }
  std::stable_sort(joins.begin(), joins.end(),
                   [](const Join& a, const Join& b) { return a.priority < b.priority; });

  std::vector<std::array<Vec2, 3>> moved;
  std::vector<Vec2> points;
  std::vector<int> slot(n, -1);  // a face of the piece being moved: its place in `moved`
  const std::vector<TabShape> shapes = tab_shapes(tab_angle_deg);
  for (const Join& j : joins) {
    int f = j.f, k = j.k;
    int g = graph.neighbour[f][k], kg = graph.neighbour_edge[f][k];
    // The smaller piece moves onto the larger one's frame.
    if (grown[of[f]].faces.size() < grown[of[g]].faces.size()) std::swap(f, g), std::swap(k, kg);
    const int a = of[f], b = of[g];
    if (a == b) continue;
    const auto& pf = out.net.points[f];
    const auto& pg = out.net.points[g];
    // g's edge kg runs the other way round f's edge k.
    const Vec2 f0 = pf[k], f1 = pf[(k + 1) % 3], g0 = pg[kg], g1 = pg[(kg + 1) % 3];
    if (!(norm(f1 - f0) > 0) || !(norm(g1 - g0) > 0)) continue;
    const Rigid move = motion(g0, g1, f1, f0);
    Grown& big = grown[a];
    Grown& small = grown[b];
    points = big.hull;
    for (Vec2 p : small.hull) points.push_back(move(p));
    for (Vec2& p : points) p = scale * p;
    std::vector<Vec2> hull = convex_hull(points);
    if (!hull_fits(hull, room.room)) continue;
    moved.clear();
    for (int h : small.faces) {
      const auto& t = out.net.points[h];
      moved.push_back({move(t[0]), move(t[1]), move(t[2])});
    }
    // The glued edge exactly where f's is.
    const std::size_t gi = static_cast<std::size_t>(
        std::find(small.faces.begin(), small.faces.end(), g) - small.faces.begin());
    moved[gi][kg] = f1;
    moved[gi][(kg + 1) % 3] = f0;
    bool overlaps = false;
    for (std::size_t i = 0; i < moved.size() && !overlaps; ++i) {
      const Box2 box = triangle_box(moved[i]);
      const auto test = [&](int c) {
        if (!overlaps && triangles_overlap(moved[i], out.net.points[c], tolerance)) overlaps = true;
      };
      if (big.grid)
        big.grid->query(box, test);
      else
        for (int c : big.faces) test(c);
    }
    if (overlaps) continue;
    if (tab_height > 0) {
      for (std::size_t i = 0; i < moved.size(); ++i) slot[small.faces[i]] = static_cast<int>(i);
      const auto at = [&](int c) -> const std::array<Vec2, 3>& {
        return slot[c] >= 0 ? moved[slot[c]] : out.net.points[c];
      };
      const Rigid back = motion(f1, f0, g0, g1);  // big's frame to small's
      // Whether a tab fits outside edge k of face h, over no other face of the joined piece.
      const auto room_for_tab = [&](int h, int k) {
        return tab_fits(
            at(h), k, shapes, tab_height,
            [&](const Triangle2& t0, const Triangle2& t1, const Box2& box) {
              bool hit = false;
              const auto test = [&](int c) {
                if (!hit && c != h)
                  hit = triangles_overlap(t0, at(c), tolerance) ||
                        triangles_overlap(t1, at(c), tolerance);
              };
              if (big.grid)
                big.grid->query(box, test);
              else
                for (int c : big.faces) test(c);
              if (small.grid) {
                Box2 back_box = Box2::empty();
                for (Vec2 p : {box.lo, box.hi, Vec2{box.lo.x, box.hi.y}, Vec2{box.hi.x, box.lo.y}})
                  back_box.add(back(p));
                small.grid->query(back_box, test);
              } else {
                for (int c : small.faces) test(c);
              }
              return hit;
            });
      };
      // Every edge this join makes a cut inside one piece (but the glued one) needs a tab's
      // room on one side, or its two sides on each other.
      bool slit = false;
      for (std::size_t i = 0; i < moved.size() && !slit; ++i) {
        const int h = small.faces[i];
        for (int k = 0; k < 3 && !slit; ++k) {
          const int c = graph.neighbour[h][k];
          if (c < 0 || of[c] != a || (h == g && k == kg)) continue;
          const int kc = graph.neighbour_edge[h][k];
          if (sides_coincide(moved[i][k], moved[i][(k + 1) % 3], at(c)[kc], at(c)[(kc + 1) % 3]))
            continue;  // glued, not cut
          slit = !room_for_tab(h, k) && !room_for_tab(c, kc);
        }
      }
      for (int h : small.faces) slot[h] = -1;
      if (slit) continue;
    }
    // Join: small's faces move into big's frame, its tree re-hung from g under f.
    for (std::size_t i = 0; i < moved.size(); ++i) {
      const int h = small.faces[i];
      out.net.points[h] = moved[i];
      of[h] = a;
      big.faces.push_back(h);
      if (big.grid) big.grid->insert(h, triangle_box(moved[i]));
    }
    for (int prev = f, cur = g; cur >= 0;) {
      const int next = out.net.parent[cur];
      out.net.parent[cur] = prev;
      prev = cur;
      cur = next;
    }
    for (Vec2& p : hull) p = (1 / scale) * p;
    big.hull = std::move(hull);
    if (!big.grid && big.faces.size() > kGridFaces) {
      big.grid = std::make_unique<OverlapGrid>();
      big.grid->reset(cell);
      for (int h : big.faces) big.grid->insert(h, triangle_box(out.net.points[h]));
    }
    small = Grown{};
  }

  // Pieces numbered by their first face.
  std::vector<int> number(n, -1);
  out.piece.assign(n, 0);
  int inputs = 0;
  for (int p : piece) inputs = std::max(inputs, p + 1);
  for (int f = 0; f < n; ++f) {
    int& id = number[of[f]];
    if (id < 0) id = out.pieces++;
    out.piece[f] = id;
  }
  out.cut_links = std::max(0, out.pieces - inputs);
  return out;
}

}  // namespace papernet
