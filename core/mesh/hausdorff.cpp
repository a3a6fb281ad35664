#include "core/mesh/hausdorff.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <utility>
#include <vector>

#include "core/errors.h"

namespace papernet {
namespace {

// Squared distance from p to triangle abc (closest-point regions as in Ericson, Real-Time
// Collision Detection, 5.1.5).
double distance2_to_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto d2of = [&](Vec3 q) { return dot(p - q, p - q); };
  if (d1 <= 0 && d2 <= 0) return d2of(a);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return d2of(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return d2of(a + (d1 / (d1 - d3)) * ab);
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return d2of(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return d2of(a + (d2 / (d2 - d6)) * ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return d2of(b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b));
  const double denom = va + vb + vc;
  if (!(denom > 0)) {  // degenerate triangle: closest of its edges
    auto seg = [&](Vec3 s, Vec3 t) {
      const Vec3 st = t - s;
      const double l = dot(st, st);
      const double u = l > 0 ? std::clamp(dot(p - s, st) / l, 0.0, 1.0) : 0.0;
      return d2of(s + u * st);
    };
    return std::min({seg(a, b), seg(b, c), seg(c, a)});
  }
  const double v = vb / denom, w = vc / denom;
  return d2of(a + v * ab + w * ac);
}

// Bounding-volume hierarchy over a mesh's faces for closest-point queries.
class FaceTree {
 public:
  explicit FaceTree(const Mesh& mesh) : mesh_(mesh), order_(mesh.faces.size()) {
    std::iota(order_.begin(), order_.end(), 0);
    centroid_.reserve(mesh.faces.size());
    for (const auto& f : mesh.faces)
      centroid_.push_back((1.0 / 3) *
                          (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]));
    nodes_.reserve(2 * mesh.faces.size() / kLeaf + 2);
    build(0, static_cast<int>(order_.size()));
  }

  double distance2(Vec3 p, int face) const {
    const auto& f = mesh_.faces[face];
    return distance2_to_triangle(p, mesh_.vertices[f[0]], mesh_.vertices[f[1]],
                                 mesh_.vertices[f[2]]);
  }

  // Closest face to p and its squared distance; `hint` (a face likely near p, or -1) primes
  // the search bound.
  std::pair<double, int> closest(Vec3 p, int hint) const {
    double best = std::numeric_limits<double>::infinity();
    int best_face = -1;
    if (hint >= 0) best = distance2(p, hint), best_face = hint;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (box_distance2(p, n) >= best) continue;
      if (n.count > 0) {
        for (int i = n.first; i < n.first + n.count; ++i) {
          const double d = distance2(p, order_[i]);
          if (d < best) best = d, best_face = order_[i];
        }
        continue;
      }
      const int left = n.first, right = n.right;
      const double dl = box_distance2(p, nodes_[left]), dr = box_distance2(p, nodes_[right]);
      if (dl < dr) {
        if (dr < best) stack[top++] = right;
        if (dl < best) stack[top++] = left;
      } else {
        if (dl < best) stack[top++] = left;
        if (dr < best) stack[top++] = right;
      }
    }
    return {best, best_face};
  }

 private:
  static constexpr int kLeaf = 4;
  struct Node {
    Vec3 lo, hi;
    int first = 0, count = 0;  // leaf: faces order_[first, first + count)
    int right = -1;            // inner node (count == 0): children `first` and `right`
  };

  static double box_distance2(Vec3 p, const Node& n) {
    const double dx = std::max({n.lo.x - p.x, 0.0, p.x - n.hi.x});
    const double dy = std::max({n.lo.y - p.y, 0.0, p.y - n.hi.y});
    const double dz = std::max({n.lo.z - p.z, 0.0, p.z - n.hi.z});
    return dx * dx + dy * dy + dz * dz;
  }

  int build(int begin, int end) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Box3 box = Box3::empty(), centroids = Box3::empty();
    for (int i = begin; i < end; ++i) {
      for (int v : mesh_.faces[order_[i]]) box.add(mesh_.vertices[v]);
      centroids.add(centroid_[order_[i]]);
    }
    nodes_[index].lo = box.lo;
    nodes_[index].hi = box.hi;
    if (end - begin <= kLeaf) {
      nodes_[index].first = begin;
      nodes_[index].count = end - begin;
      return index;
    }
    const Vec3 ext = centroids.size();
    const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
    auto coord = [&](int f) {
      const Vec3 c = centroid_[f];
      return axis == 0 ? c.x : axis == 1 ? c.y : c.z;
    };
    const int mid = (begin + end) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](int a, int b) { return coord(a) < coord(b); });
    const int left = build(begin, mid);
    const int right = build(mid, end);
    nodes_[index].first = left;
    nodes_[index].count = 0;
    nodes_[index].right = right;
    return index;
  }

  const Mesh& mesh_;
  std::vector<int> order_;
  std::vector<Vec3> centroid_;
  std::vector<Node> nodes_;
};

struct Patch {
  std::array<Vec3, 3> p;
  std::array<double, 3> d;  // distance of each corner to the other surface
  std::array<int, 3> near;  // the face of the other surface closest to each corner
  double upper = 0;         // no point of the patch is farther than this from the other surface
  bool operator<(const Patch& o) const { return upper < o.upper; }
};

void bound(Patch& patch, const FaceTree& tree) {
  const double longest =
      std::sqrt(std::max({dot(patch.p[1] - patch.p[0], patch.p[1] - patch.p[0]),
                          dot(patch.p[2] - patch.p[1], patch.p[2] - patch.p[1]),
                          dot(patch.p[0] - patch.p[2], patch.p[0] - patch.p[2])}));
  double upper = std::max({patch.d[0], patch.d[1], patch.d[2]}) + longest / std::sqrt(3.0);
  for (int j = 0; j < 3; ++j) {
    double worst = 0;
    for (int i = 0; i < 3 && worst < upper; ++i)
      worst = std::max(worst,
                       i == j ? patch.d[i] : std::sqrt(tree.distance2(patch.p[i], patch.near[j])));
    upper = std::min(upper, worst);
  }
  patch.upper = upper;
}

// One direction, from the surface of `from` to the one in `tree`. Raises `attained` to the
// largest distance reached by a sampled point; returns an upper bound of the direction.
double one_side(const Mesh& from, const FaceTree& tree, double& attained, double rel, double abs,
                std::size_t max_refinements) {
  std::vector<double> vd(from.vertices.size(), -1);
  std::vector<int> vn(from.vertices.size(), -1);
  int hint = -1;
  for (const auto& f : from.faces)
    for (int v : f) {
      if (vd[v] >= 0) continue;
      const auto [d2, face] = tree.closest(from.vertices[v], hint);
      vd[v] = std::sqrt(d2);
      vn[v] = hint = face;
      attained = std::max(attained, vd[v]);
    }
  auto done = [&](double upper) { return upper <= std::max(attained * (1 + rel), attained + abs); };
  std::priority_queue<Patch> heap;
  for (const auto& f : from.faces) {
    Patch patch;
    for (int i = 0; i < 3; ++i) {
      patch.p[i] = from.vertices[f[i]];
      patch.d[i] = vd[f[i]];
      patch.near[i] = vn[f[i]];
    }
    bound(patch, tree);
    if (!done(patch.upper)) heap.push(patch);
  }
  std::size_t refined = 0;
  while (!heap.empty()) {
    const Patch top = heap.top();
    if (done(top.upper) || refined >= max_refinements) return std::max(top.upper, attained);
    heap.pop();
    ++refined;
    std::array<Vec3, 3> m;
    std::array<double, 3> md;
    std::array<int, 3> mn;
    for (int i = 0; i < 3; ++i) {
      m[i] = 0.5 * (top.p[i] + top.p[(i + 1) % 3]);
      const auto [d2, face] = tree.closest(m[i], top.near[i]);
      md[i] = std::sqrt(d2);
      mn[i] = face;
      attained = std::max(attained, md[i]);
    }
    // Corners then edge midpoints (m[i] between corners i and i+1): four children.
    const Patch children[4] = {
        {{top.p[0], m[0], m[2]}, {top.d[0], md[0], md[2]}, {top.near[0], mn[0], mn[2]}, 0},
        {{m[0], top.p[1], m[1]}, {md[0], top.d[1], md[1]}, {mn[0], top.near[1], mn[1]}, 0},
        {{m[2], m[1], top.p[2]}, {md[2], md[1], top.d[2]}, {mn[2], mn[1], top.near[2]}, 0},
        {{m[0], m[1], m[2]}, {md[0], md[1], md[2]}, {mn[0], mn[1], mn[2]}, 0}};
    for (Patch child : children) {
      bound(child, tree);
      if (!done(child.upper)) heap.push(child);
    }
  }
  return attained;
}

}  // namespace

HausdorffResult hausdorff_distance(const Mesh& a, const Mesh& b, const HausdorffOptions& options) {
  if (a.faces.empty() || b.faces.empty())
    throw InvalidInputException("Hausdorff distance needs two meshes with faces");
  const double diagonal = bounding_box_diagonal(a);
  const double scale = diagonal > 0 ? diagonal : 1;
  const double abs = options.absolute_accuracy * scale;
  const FaceTree tree_a(a), tree_b(b);
  double attained = 0;
  const double ab =
      one_side(a, tree_b, attained, options.relative_accuracy, abs, options.max_refinements);
  const double ba =
      one_side(b, tree_a, attained, options.relative_accuracy, abs, options.max_refinements);
  // Bounds from the first direction were judged against a smaller `attained`: still valid.
  return {attained / scale, std::max({ab, ba, attained}) / scale};
}

double approximation_distance(const Mesh& input, const Mesh& approximation) {
  // A bounded amount of refinement (20,000 triangles per direction): CAD meshes kept exactly by
  // the quadrics would otherwise refine their flat sides towards the absolute accuracy for a
  // long time.
  HausdorffOptions accuracy;
  accuracy.max_refinements = 20'000;
  return hausdorff_distance(input, approximation, accuracy).distance;
}

}  // namespace papernet
