#include "core/mesh/thin_faces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/mesh/dual_graph.h"

namespace papernet {
namespace {

// Flip passes at most: each pass flips at most one edge of each face, and thin faces are few.
constexpr int kMostPasses = 20;

double distance2_to_segment(Vec3 p, Vec3 a, Vec3 b) {
  const Vec3 ab = b - a;
  const double length2 = dot(ab, ab);
  const double t = length2 > 0 ? std::clamp(dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  const Vec3 q = a + t * ab;
  return dot(p - q, p - q);
}

double height(Vec3 a, Vec3 b, Vec3 c) {
  const double longest = std::max({norm(b - a), norm(c - b), norm(a - c)});
  return longest > 0 ? norm(cross(b - a, c - a)) / longest : 0;
}

}  // namespace

double face_height(const Mesh& mesh, int face) {
  const auto& t = mesh.faces[face];
  return height(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
}

std::size_t thicken_thin_faces(Mesh& mesh, double min_height, double max_move) {
  std::size_t flips = 0;
  const auto nf = static_cast<int>(mesh.faces.size());
  // How far each face may be from the surface given: the flips that made it, added up.
  std::vector<double> moved(mesh.faces.size(), 0);
  for (int pass = 0; pass < kMostPasses; ++pass) {
    // Each edge's faces, with the corner where the edge starts in each; an edge of more than two
    // faces is never flipped (count).
    struct Sides {
      std::array<std::pair<int, int>, 2> at{};
      int count = 0;
    };
    std::unordered_map<std::uint64_t, Sides> edges;
    edges.reserve(3 * mesh.faces.size());
    for (int f = 0; f < nf; ++f)
      for (int i = 0; i < 3; ++i) {
        Sides& s = edges[edge_key(mesh.faces[f][i], mesh.faces[f][(i + 1) % 3])];
        if (s.count < 2) s.at[s.count] = {f, i};
        ++s.count;
      }
    std::vector<char> touched(mesh.faces.size(), 0);
    std::size_t flipped = 0;
    for (int f = 0; f < nf; ++f) {
      if (touched[f] || face_height(mesh, f) >= min_height) continue;
      // The face's longest edge: across it, a sliver's corner lies almost on it.
      const auto& t = mesh.faces[f];
      int k = 0;
      for (int i = 1; i < 3; ++i)
        if (norm(mesh.vertices[t[(i + 1) % 3]] - mesh.vertices[t[i]]) >
            norm(mesh.vertices[t[(k + 1) % 3]] - mesh.vertices[t[k]]))
          k = i;
      const auto it = edges.find(edge_key(t[k], t[(k + 1) % 3]));
      if (it->second.count != 2) continue;
      const auto [g, gk] = it->second.at[0].first == f ? it->second.at[1] : it->second.at[0];
      if (g == f || touched[g]) continue;
      // f = (a, b, c) from corner k, g = (b, a, d) from corner gk.
      const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      const int d = mesh.faces[g][(gk + 2) % 3];
      if (mesh.faces[g][gk] != b || c == d || edges.count(edge_key(c, d))) continue;
      const Vec3 pa = mesh.vertices[a], pb = mesh.vertices[b], pc = mesh.vertices[c],
                 pd = mesh.vertices[d];
      const double before = std::min(height(pa, pb, pc), height(pb, pa, pd));
      const double after = std::min(height(pc, pa, pd), height(pd, pb, pc));
      if (!(after > before)) continue;
      const Vec3 normal = cross(pb - pa, pc - pa) + cross(pa - pb, pd - pb);
      if (!(dot(cross(pa - pc, pd - pc), normal) > 0) ||
          !(dot(cross(pb - pd, pc - pd), normal) > 0))
        continue;
      // The surface moves at most the distance of c (or of d) from the edge ab: split both the
      // old faces and the new at c's nearest point on ab, each part has two corners on a face
      // of the other pair and the third within that distance of it (and the distance to one
      // triangle is convex, largest at a corner).
      const double step =
          std::sqrt(std::min(distance2_to_segment(pc, pa, pb), distance2_to_segment(pd, pa, pb)));
      const double move = std::max(moved[f], moved[g]) + step;
      if (move > max_move) continue;
      mesh.faces[f] = {c, a, d};
      mesh.faces[g] = {d, b, c};
      edges[edge_key(c, d)] = {};  // taken: no other flip of this pass makes it
      touched[f] = touched[g] = 1;
      moved[f] = moved[g] = move;
      ++flipped;
    }
    flips += flipped;
    if (flipped == 0) break;
  }
  return flips;
}

}  // namespace papernet
