#include "core/mesh/face_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace papernet {

// Closest-point regions as in Ericson, Real-Time Collision Detection, 5.1.5.
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

FaceTree::FaceTree(const Mesh& mesh) : mesh_(mesh), order_(mesh.faces.size()) {
  std::iota(order_.begin(), order_.end(), 0);
  centroid_.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces)
    centroid_.push_back((1.0 / 3) *
                        (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]));
  nodes_.reserve(2 * mesh.faces.size() / kLeaf + 2);
  build(0, static_cast<int>(order_.size()));
}

double FaceTree::distance2(Vec3 p, int face) const {
  const auto& f = mesh_.faces[face];
  return distance2_to_triangle(p, mesh_.vertices[f[0]], mesh_.vertices[f[1]], mesh_.vertices[f[2]]);
}

std::pair<double, int> FaceTree::closest(Vec3 p, int hint, double enough2) const {
  double best = std::numeric_limits<double>::infinity();
  int best_face = -1;
  if (hint >= 0) best = distance2(p, hint), best_face = hint;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0 && best > enough2) {
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

double FaceTree::box_distance2(Vec3 p, const Node& n) {
  const double dx = std::max({n.lo.x - p.x, 0.0, p.x - n.hi.x});
  const double dy = std::max({n.lo.y - p.y, 0.0, p.y - n.hi.y});
  const double dz = std::max({n.lo.z - p.z, 0.0, p.z - n.hi.z});
  return dx * dx + dy * dy + dz * dz;
}

int FaceTree::build(int begin, int end) {
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

}  // namespace papernet
