#include "core/unfold/net_check.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace papernet {

namespace {

class Collector {
 public:
  Collector(NetCheckReport& report, std::size_t max) : report_(report), max_(max) {}
  void fail(const std::string& message) {
    ++report_.failure_count;
    if (report_.failures.size() < max_) report_.failures.push_back(message);
  }

 private:
  NetCheckReport& report_;
  std::size_t max_;
};

std::string face_name(std::size_t f) { return "face " + std::to_string(f); }

double orient(Vec2 a, Vec2 b, Vec2 c) { return cross(b - a, c - a); }

// Segments pq and rs cross at a point inside both: each one's ends lie strictly on opposite
// sides of the other's line, farther than `tiny` from it. Collinear and touching segments do
// not cross; the callers shrink triangles first, so touching never means overlapping.
bool segments_cross(Vec2 p, Vec2 q, Vec2 r, Vec2 s, double tiny) {
  const double lrs = norm(s - r), lpq = norm(q - p);
  const double d1 = orient(r, s, p), d2 = orient(r, s, q), d3 = orient(p, q, r),
               d4 = orient(p, q, s);
  const auto apart = [tiny](double x, double y, double len) {
    return (x > tiny * len && y < -tiny * len) || (x < -tiny * len && y > tiny * len);
  };
  return apart(d1, d2, lrs) && apart(d3, d4, lpq);
}

// Point inside or on the counter-clockwise triangle t.
bool inside(const std::array<Vec2, 3>& t, Vec2 p) {
  return orient(t[0], t[1], p) >= 0 && orient(t[1], t[2], p) >= 0 && orient(t[2], t[0], p) >= 0;
}

// The triangle shrunk towards its incentre by `d`; false when it vanishes (thinner than d).
bool shrink(const std::array<Vec2, 3>& t, double d, std::array<Vec2, 3>& out) {
  const double a = norm(t[1] - t[2]), b = norm(t[2] - t[0]), c = norm(t[0] - t[1]);
  const double perimeter = a + b + c;
  const Vec2 centre = (1.0 / perimeter) * (a * t[0] + b * t[1] + c * t[2]);
  const double inradius = std::abs(orient(t[0], t[1], t[2])) / perimeter;
  if (inradius <= d) return false;
  const double s = 1 - d / inradius;
  for (int k = 0; k < 3; ++k) out[k] = centre + s * (t[k] - centre);
  return true;
}

// Interiors of two counter-clockwise triangles intersect by more than d: a disk of radius d fits
// inside both (the triangles shrunk by d, their inner parallel bodies, meet).
bool interiors_meet(const std::array<Vec2, 3>& t, const std::array<Vec2, 3>& u, double d) {
  const double tiny = 1e-6 * d;
  std::array<Vec2, 3> a, b;
  if (!shrink(t, d, a) || !shrink(u, d, b)) return false;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segments_cross(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3], tiny)) return true;
  for (int k = 0; k < 3; ++k)
    if (inside(a, b[k]) || inside(b, a[k])) return true;
  return false;
}

Box2 box_of(const std::array<Vec2, 3>& t) {
  Box2 b = Box2::empty();
  for (const Vec2 p : t) b.add(p);
  return b;
}

bool boxes_meet(const Box2& a, const Box2& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y;
}

// False only when an edge line of the triangle has the whole box strictly outside it (the axes of
// the box itself are the callers' box test). Then nothing inside the box meets the triangle: the
// descent below skips such nodes, which keeps long diagonal slivers from visiting every face
// their bounding box covers.
bool triangle_may_meet_box(const std::array<Vec2, 3>& t, const Box2& box) {
  // The inside of a counter-clockwise triangle is left of its edges; a mirrored one's, right.
  const double sign = orient(t[0], t[1], t[2]) < 0 ? -1 : 1;
  for (int k = 0; k < 3; ++k) {
    const Vec2 p = t[k], e = t[(k + 1) % 3] - p;
    // The box corner farthest inside.
    const Vec2 corner{sign * e.y <= 0 ? box.hi.x : box.lo.x, sign * e.x >= 0 ? box.hi.y : box.lo.y};
    if (sign * cross(e, corner - p) < 0) return false;
  }
  return true;
}

// A static bounding-box tree over the net's triangles, split at the median of the longer axis:
// queries cost O(log n) plus the faces near the query, whatever the faces' sizes (one face may
// span the whole net, another be a sliver a millionth as wide).
class TriangleTree {
 public:
  explicit TriangleTree(const std::vector<std::array<Vec2, 3>>& triangles) : tri_(triangles) {
    const std::size_t n = tri_.size();
    box_.reserve(n);
    centre2_.reserve(n);
    for (const auto& t : tri_) {
      box_.push_back(box_of(t));
      centre2_.push_back(box_.back().lo + box_.back().hi);
    }
    items_.resize(n);
    for (std::size_t i = 0; i < n; ++i) items_[i] = static_cast<int>(i);
    if (n == 0) return;
    nodes_.push_back({Box2::empty(), 0, n, -1});
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      Node node = nodes_[i];
      for (std::size_t j = node.begin; j < node.end; ++j) node.box.add(box_[items_[j]]);
      nodes_[i].box = node.box;
      if (node.end - node.begin <= kLeaf) continue;
      const Vec2 size = node.box.size();
      const bool by_x = size.x >= size.y;
      const std::size_t mid = (node.begin + node.end) / 2;
      std::nth_element(items_.begin() + static_cast<std::ptrdiff_t>(node.begin),
                       items_.begin() + static_cast<std::ptrdiff_t>(mid),
                       items_.begin() + static_cast<std::ptrdiff_t>(node.end), [&](int a, int b) {
                         return by_x ? centre2_[a].x < centre2_[b].x
                                     : centre2_[a].y < centre2_[b].y;
                       });
      nodes_[i].first_child = static_cast<int>(nodes_.size());
      nodes_.push_back({Box2::empty(), node.begin, mid, -1});
      nodes_.push_back({Box2::empty(), mid, node.end, -1});
    }
  }

  // Calls visit(g) for every face g whose box meets face f's box and whose box the triangle f
  // may meet (a superset of the faces f can overlap).
  template <class Visit>
  void near(std::size_t f, Visit&& visit) {
    if (nodes_.empty()) return;
    const Box2& box = box_[f];
    stack_.assign(1, 0);
    while (!stack_.empty()) {
      const Node& node = nodes_[static_cast<std::size_t>(stack_.back())];
      stack_.pop_back();
      if (!boxes_meet(box, node.box) || !triangle_may_meet_box(tri_[f], node.box)) continue;
      if (node.first_child >= 0) {
        stack_.push_back(node.first_child);
        stack_.push_back(node.first_child + 1);
        continue;
      }
      for (std::size_t j = node.begin; j < node.end; ++j)
        if (boxes_meet(box, box_[items_[j]])) visit(static_cast<std::size_t>(items_[j]));
    }
  }

 private:
  static constexpr std::size_t kLeaf = 4;
  struct Node {
    Box2 box;
    std::size_t begin = 0, end = 0;
    int first_child = -1;  // the two children are first_child and first_child + 1
  };
  const std::vector<std::array<Vec2, 3>>& tri_;
  std::vector<Box2> box_;
  std::vector<Vec2> centre2_;  // twice each box's centre
  std::vector<int> items_;
  std::vector<Node> nodes_;
  std::vector<int> stack_;
};

}  // namespace

std::string NetCheckReport::summary() const {
  std::string s;
  for (const std::string& f : failures) s += (s.empty() ? "" : "; ") + f;
  if (failure_count > failures.size())
    s += "; and " + std::to_string(failure_count - failures.size()) + " more";
  return s;
}

NetCheckReport check_net(const Mesh& mesh, const Net& net, const NetCheckOptions& options) {
  NetCheckReport report;
  Collector out(report, options.max_messages);
  const std::size_t nf = mesh.faces.size();
  if (net.parent.size() != nf || net.points.size() != nf) {
    out.fail("the net has " + std::to_string(net.parent.size()) + " parents and " +
             std::to_string(net.points.size()) + " triangles for " + std::to_string(nf) + " faces");
    return report;
  }
  const double diag = options.diagonal > 0 ? options.diagonal : bounding_box_diagonal(mesh);
  const double len_tol = options.length_tolerance * diag;

  // Congruence with orientation: edge lengths as on the mesh, and the third corner where the face
  // lands when one edge is laid where the net has it, with the face on its left
  // (counter-clockwise), within the length tolerance. A sign test of the 2D area instead would
  // reject valid slivers whose height is within rounding of zero.
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& c = mesh.faces[f];
    const auto& p = net.points[f];
    bool lengths_ok = true;
    for (int k = 0; k < 3 && lengths_ok; ++k) {
      const double l3 = norm(mesh.vertices[c[(k + 1) % 3]] - mesh.vertices[c[k]]);
      const double l2 = norm(p[(k + 1) % 3] - p[k]);
      if (!(std::abs(l3 - l2) <= len_tol)) {
        out.fail(face_name(f) + " edge " + std::to_string(k) + " is " + std::to_string(l2) +
                 " long in the net but " + std::to_string(l3) + " on the mesh");
        lengths_ok = false;
      }
    }
    if (!lengths_ok) continue;
    // Laid along its longest edge k: the placement of the third corner then depends least on
    // rounding in the other two.
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (norm(mesh.vertices[c[(i + 1) % 3]] - mesh.vertices[c[i]]) >
          norm(mesh.vertices[c[(k + 1) % 3]] - mesh.vertices[c[k]]))
        k = i;
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    const Vec3 a = mesh.vertices[c[k]], e3 = mesh.vertices[c[k1]] - a,
               d3 = mesh.vertices[c[k2]] - a;
    const Vec2 e2 = p[k1] - p[k];
    const double len2 = norm(e2), len3 = norm(e3);
    if (!(len2 > 0) || !(len3 > 0)) {
      out.fail(face_name(f) + " is not congruent to its face");
      continue;
    }
    const double along = dot(d3, e3) / len3, left = norm(cross(e3, d3)) / len3;
    const Vec2 u = (1.0 / len2) * e2, v{-u.y, u.x};
    const Vec2 base = p[k] + along * u;
    if (norm(p[k2] - (base + left * v)) <= len_tol) continue;
    if (norm(p[k2] - (base - left * v)) <= len_tol)
      out.fail(face_name(f) + " is flipped in the net");
    else
      out.fail(face_name(f) + " is not congruent to its face");
  }

  // One spanning tree: one root, parents in range, every face reaches the root.
  std::size_t roots = 0;
  bool parents_ok = true;
  for (std::size_t f = 0; f < nf; ++f) {
    const int p = net.parent[f];
    if (p == -1) {
      ++roots;
    } else if (p < 0 || static_cast<std::size_t>(p) >= nf || static_cast<std::size_t>(p) == f) {
      out.fail(face_name(f) + " has parent " + std::to_string(p) + ", which is not a face");
      parents_ok = false;
    }
  }
  if (roots != 1) out.fail("the net has " + std::to_string(roots) + " roots instead of one");
  if (parents_ok) {
    std::vector<int> state(nf, 0);  // 0 unknown, 1 on the current walk, 2 reaches the root
    std::vector<std::size_t> walk;
    for (std::size_t s = 0; s < nf; ++s) {
      walk.clear();
      std::size_t f = s;
      for (;;) {
        if (state[f] == 2) break;
        if (state[f] == 1) {
          out.fail("the parent links of " + face_name(f) + " form a cycle");
          break;
        }
        state[f] = 1;
        walk.push_back(f);
        if (net.parent[f] < 0) break;
        f = static_cast<std::size_t>(net.parent[f]);
      }
      for (std::size_t w : walk) state[w] = 2;
    }
  }

  // Glued links: a shared mesh edge at the same 2D place in both faces.
  for (std::size_t f = 0; f < nf && parents_ok; ++f) {
    const int p = net.parent[f];
    if (p < 0) continue;
    int shared = 0;
    bool glued = true;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (mesh.faces[f][i] == mesh.faces[p][j]) {
          ++shared;
          if (!(norm(net.points[f][i] - net.points[p][j]) <= len_tol)) glued = false;
        }
    if (shared < 2)
      out.fail(face_name(f) + " and its parent " + face_name(p) + " share no edge");
    else if (!glued)
      out.fail(face_name(f) + " is not glued to its parent " + face_name(p) +
               ": the shared edge is at different places");
  }

  // Overlaps: every pair whose boxes meet, found through a bounding-box tree (no assumption on
  // the faces' sizes).
  for (const auto& t : net.points)
    for (const Vec2 p : t)
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) return report;  // failed congruence above
  const double d = options.overlap_tolerance * diag;
  TriangleTree tree(net.points);
  for (std::size_t f = 0; f < nf; ++f)
    tree.near(f, [&](std::size_t g) {
      if (g > f && interiors_meet(net.points[f], net.points[g], d)) {
        ++report.overlapping_pairs;
        out.fail(face_name(f) + " and " + face_name(g) + " overlap");
      }
    });
  return report;
}

}  // namespace papernet
