// Pieces grown from single faces, flattest folds first (print/grow.h, grow_to_fit).
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
#include "print/grow.h"
#include "print/internal/number_pieces.h"

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

// The pieces grown so far: each face's place in its piece's frame and tree (`out.net`), the
// pieces by the index of a face in `grown`, and the piece each face is in.
struct Growth {
  FitPieces out;
  std::vector<Grown> grown;
  std::vector<int> of;
};

// Joins pieces across edges (grow_to_fit): the growth's constants and scratch space.
class Grower {
 public:
  Grower(const Mesh& mesh, double scale, FitRoom room, double tab_height, double tab_angle_deg)
      : mesh_(mesh),
        graph_(build_dual_graph(mesh)),
        tolerance_(kOverlapTolerance * bounding_box_diagonal(mesh)),
        cell_(std::max(median_edge_length(mesh), 1e-12)),
        scale_(scale),
        room_(room),
        tab_height_(tab_height),
        shapes_(tab_shapes(tab_angle_deg)),
        slot_(mesh.faces.size(), -1) {}

  const DualGraph& graph() const { return graph_; }

  // Every face a piece of its own, laid flat.
  Growth start() const;
  // Joins the pieces on the two sides of j's edge when the joined piece lies flat without
  // overlap, fits the room and (with a tab height) leaves no slit without room for a tab.
  void join(Growth& growth, const Join& j);
  // Piece p's faces become pieces of their own again, each where it lies.
  void dissolve(Growth& growth, int p) const;
  // A copy of `growth` (its grids built again).
  Growth copy(const Growth& growth) const;

 private:
  void add_grid(Grown& piece, const Net& net) const {
    piece.grid = std::make_unique<OverlapGrid>();
    piece.grid->reset(cell_);
    for (int h : piece.faces) piece.grid->insert(h, triangle_box(net.points[h]));
  }
  std::vector<Vec2> face_hull(const Net& net, int f) const {
    return convex_hull({net.points[f].begin(), net.points[f].end()});
  }

  const Mesh& mesh_;
  const DualGraph graph_;
  const double tolerance_, cell_, scale_;
  const FitRoom room_;
  const double tab_height_;
  const std::vector<TabShape> shapes_;
  std::vector<std::array<Vec2, 3>> moved_;
  std::vector<Vec2> points_;
  std::vector<int> slot_;  // a face of the piece being moved: its place in `moved_`
};

Growth Grower::start() const {
  const auto n = static_cast<int>(mesh_.faces.size());
  Growth growth;
  FitPieces& out = growth.out;
  out.large.assign(n, 0);
  out.net.parent.assign(n, -1);
  out.net.points.resize(n);
  growth.grown.resize(n);
  growth.of.resize(n);
  for (int f = 0; f < n; ++f) {
    out.net.points[f] = place_root(mesh_, f, face_shape(mesh_, f));
    growth.grown[f].faces = {f};
    growth.grown[f].hull = face_hull(out.net, f);
    std::vector<Vec2> mm;
    for (Vec2 p : growth.grown[f].hull) mm.push_back(scale_ * p);
    out.large[f] = !hull_fits(mm, room_.room);  // alone: no join fits either
    growth.of[f] = f;
  }
  return growth;
}

void Grower::dissolve(Growth& growth, int p) const {
  const std::vector<int> faces = std::move(growth.grown[p].faces);
  for (int h : faces) {
    growth.out.net.parent[h] = -1;
    growth.grown[h] = Grown{{h}, face_hull(growth.out.net, h), nullptr};
    growth.of[h] = h;
  }
}

Growth Grower::copy(const Growth& growth) const {
  Growth out{growth.out, std::vector<Grown>(growth.grown.size()), growth.of};
  for (std::size_t p = 0; p < growth.grown.size(); ++p) {
    out.grown[p].faces = growth.grown[p].faces;
    out.grown[p].hull = growth.grown[p].hull;
    if (growth.grown[p].grid) add_grid(out.grown[p], out.out.net);
  }
  return out;
}

void Grower::join(Growth& growth, const Join& j) {
  Net& net = growth.out.net;
  std::vector<int>& of = growth.of;
  int f = j.f, k = j.k;
  int g = graph_.neighbour[f][k], kg = graph_.neighbour_edge[f][k];
  // The smaller piece moves onto the larger one's frame.
  if (growth.grown[of[f]].faces.size() < growth.grown[of[g]].faces.size())
    std::swap(f, g), std::swap(k, kg);
  const int a = of[f], b = of[g];
  if (a == b) return;
  const auto& pf = net.points[f];
  const auto& pg = net.points[g];
  // g's edge kg runs the other way round f's edge k.
  const Vec2 f0 = pf[k], f1 = pf[(k + 1) % 3], g0 = pg[kg], g1 = pg[(kg + 1) % 3];
  if (!(norm(f1 - f0) > 0) || !(norm(g1 - g0) > 0)) return;
  const Rigid move = motion(g0, g1, f1, f0);
  Grown& big = growth.grown[a];
  Grown& small = growth.grown[b];
  points_ = big.hull;
  for (Vec2 p : small.hull) points_.push_back(move(p));
  for (Vec2& p : points_) p = scale_ * p;
  std::vector<Vec2> hull = convex_hull(points_);
  if (!hull_fits(hull, room_.room)) return;
  moved_.clear();
  for (int h : small.faces) {
    const auto& t = net.points[h];
    moved_.push_back({move(t[0]), move(t[1]), move(t[2])});
  }
  // The glued edge exactly where f's is.
  const std::size_t gi = static_cast<std::size_t>(
      std::find(small.faces.begin(), small.faces.end(), g) - small.faces.begin());
  moved_[gi][kg] = f1;
  moved_[gi][(kg + 1) % 3] = f0;
  bool overlaps = false;
  for (std::size_t i = 0; i < moved_.size() && !overlaps; ++i) {
    const Box2 box = triangle_box(moved_[i]);
    const auto test = [&](int c) {
      if (!overlaps && triangles_overlap(moved_[i], net.points[c], tolerance_)) overlaps = true;
    };
    if (big.grid)
      big.grid->query(box, test);
    else
      for (int c : big.faces) test(c);
  }
  if (overlaps) return;
  if (tab_height_ > 0) {
    for (std::size_t i = 0; i < moved_.size(); ++i) slot_[small.faces[i]] = static_cast<int>(i);
    const auto at = [&](int c) -> const std::array<Vec2, 3>& {
      return slot_[c] >= 0 ? moved_[slot_[c]] : net.points[c];
    };
    const Rigid back = motion(f1, f0, g0, g1);  // big's frame to small's
    // Whether a tab fits outside edge k of face h, over no other face of the joined piece.
    const auto room_for_tab = [&](int h, int k) {
      return tab_fits(
          at(h), k, shapes_, tab_height_,
          [&](const Triangle2& t0, const Triangle2& t1, const Box2& box) {
            bool hit = false;
            const auto test = [&](int c) {
              if (!hit && c != h)
                hit = triangles_overlap(t0, at(c), tolerance_) ||
                      triangles_overlap(t1, at(c), tolerance_);
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
    for (std::size_t i = 0; i < moved_.size() && !slit; ++i) {
      const int h = small.faces[i];
      for (int k = 0; k < 3 && !slit; ++k) {
        const int c = graph_.neighbour[h][k];
        if (c < 0 || of[c] != a || (h == g && k == kg)) continue;
        const int kc = graph_.neighbour_edge[h][k];
        if (sides_coincide(moved_[i][k], moved_[i][(k + 1) % 3], at(c)[kc], at(c)[(kc + 1) % 3]))
          continue;  // glued, not cut
        slit = !room_for_tab(h, k) && !room_for_tab(c, kc);
      }
    }
    for (int h : small.faces) slot_[h] = -1;
    if (slit) return;
  }
  // Join: small's faces move into big's frame, its tree re-hung from g under f.
  for (std::size_t i = 0; i < moved_.size(); ++i) {
    const int h = small.faces[i];
    net.points[h] = moved_[i];
    of[h] = a;
    big.faces.push_back(h);
    if (big.grid) big.grid->insert(h, triangle_box(moved_[i]));
  }
  for (int prev = f, cur = g; cur >= 0;) {
    const int next = net.parent[cur];
    net.parent[cur] = prev;
    prev = cur;
    cur = next;
  }
  for (Vec2& p : hull) p = (1 / scale_) * p;
  big.hull = std::move(hull);
  if (!big.grid && big.faces.size() > kGridFaces) add_grid(big, net);
  small = Grown{};
}

int count_pieces(const Growth& growth) {
  int pieces = 0;
  for (const Grown& p : growth.grown) pieces += !p.faces.empty();
  return pieces;
}

}  // namespace

FitPieces grow_to_fit(const Mesh& mesh, const std::vector<int>& piece, double scale, FitRoom room,
                      double tab_height, double tab_angle_deg, std::size_t regrow_faces) {
  const auto n = static_cast<int>(mesh.faces.size());
  Grower grower(mesh, scale, room, tab_height, tab_angle_deg);
  const DualGraph& graph = grower.graph();
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

  Growth growth = grower.start();
  for (const Join& j : joins) grower.join(growth, j);

  // Small pieces left between large ones (no join of the whole fitted): their faces, each
  // alone, join the pieces around them first, then each other.
  if (regrow_faces > 0) {
    Growth again = grower.copy(growth);
    std::vector<char> loose(n, 0);
    for (int p = 0; p < n; ++p) {
      const std::size_t size = again.grown[p].faces.size();
      if (size == 0 || size > regrow_faces) continue;
      for (int h : again.grown[p].faces) loose[h] = 1;
      grower.dissolve(again, p);
    }
    for (const Join& j : joins)
      if (loose[j.f] != loose[graph.neighbour[j.f][j.k]]) grower.join(again, j);
    for (const Join& j : joins) grower.join(again, j);
    if (count_pieces(again) < count_pieces(growth)) growth = std::move(again);
  }

  print_detail::number_pieces(std::move(growth.of), piece, growth.out);
  return std::move(growth.out);
}

void print_detail::number_pieces(std::vector<int> of, const std::vector<int>& part,
                                 FitPieces& out) {
  std::vector<int> number(of.size(), -1);
  out.piece.assign(of.size(), 0);
  out.pieces = 0;
  int inputs = 0;
  for (int p : part) inputs = std::max(inputs, p + 1);
  for (std::size_t f = 0; f < of.size(); ++f) {
    int& id = number[of[f]];
    if (id < 0) id = out.pieces++;
    out.piece[f] = id;
  }
  out.cut_links = std::max(0, out.pieces - inputs);
}

}  // namespace papernet
