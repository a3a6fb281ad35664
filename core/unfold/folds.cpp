#include "core/unfold/folds.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <unordered_map>

#include "core/errors.h"

namespace papernet {

double fold_angle(const Mesh& mesh, int f, int g) {
  const Vec3 nf = face_normal(mesh, f), ng = face_normal(mesh, g);
  const double angle = std::atan2(norm(cross(nf, ng)), dot(nf, ng));
  // The vertex of g that is not in f lies below f's plane when the edge is convex.
  for (int v : mesh.faces[g]) {
    const auto& ff = mesh.faces[f];
    if (v == ff[0] || v == ff[1] || v == ff[2]) continue;
    const double side = dot(nf, mesh.vertices[v] - mesh.vertices[ff[0]]);
    return side <= 0 ? angle : -angle;
  }
  return 0;
}

bool sides_coincide(Vec2 a0, Vec2 a1, Vec2 b0, Vec2 b1) {
  const double tol = 1e-6 * std::max(norm(a1 - a0), 1e-300);
  return norm(a0 - b1) <= tol && norm(a1 - b0) <= tol;
}

namespace {

/// True when side b lies on side a in the net: the same two points, in opposite order.
bool coincide(const Net& net, EdgeSide a, EdgeSide b) {
  return sides_coincide(net.points[a.face][a.k], net.points[a.face][(a.k + 1) % 3],
                        net.points[b.face][b.k], net.points[b.face][(b.k + 1) % 3]);
}

}  // namespace

std::vector<NetEdge> classify_edges(const Mesh& mesh, const Net& net, const FoldOptions& options) {
  std::vector<NetEdge> edges;
  std::unordered_map<std::uint64_t, int> index;  // undirected vertex pair -> edges position
  const int nf = static_cast<int>(mesh.faces.size());
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = mesh.faces[f][k], w = mesh.faces[f][(k + 1) % 3];
      const std::uint64_t key = (std::uint64_t{std::min(u, w)} << 32) | std::max(u, w);
      const auto [it, fresh] = index.try_emplace(key, static_cast<int>(edges.size()));
      if (fresh) {
        edges.push_back({EdgeKind::Cut, {f, k}, {}, 0, -1});
        continue;
      }
      NetEdge& e = edges[it->second];
      if (e.b.face >= 0)
        throw TopologyException("edge (" + std::to_string(u) + ", " + std::to_string(w) +
                                ") has more than two faces");
      e.b = {f, k};
    }
  }
  const double flat = options.flat_angle_deg * std::numbers::pi / 180;
  int cuts = 0;
  for (NetEdge& e : edges) {
    if (e.b.face < 0) continue;  // boundary: cut, no partner, no label
    const int f = e.a.face, g = e.b.face;
    // A tree link whose sides meet, or two faces that meet along this edge in the net although
    // no tree link joins them ("glued without a tree link"): the paper is one piece there, so
    // it is folded, not cut, and needs no tab and no label.
    const bool glued = coincide(net, e.a, e.b);
    if (!glued) {
      e.cut_index = cuts++;
      continue;
    }
    e.fold = fold_angle(mesh, f, g);
    e.kind = std::abs(e.fold) < flat ? EdgeKind::Flat
             : e.fold > 0            ? EdgeKind::Mountain
                                     : EdgeKind::Valley;
  }
  return edges;
}

}  // namespace papernet
