#include "core/unfold/unfold_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_set>

#include "core/errors.h"
#include "core/random.h"
#include "core/union_find.h"

namespace papernet {

FaceShape face_shape(const Mesh& mesh, int f) {
  FaceShape s;
  const auto& c = mesh.faces[f];
  for (int k = 0; k < 3; ++k) {
    const Vec3 a = mesh.vertices[c[k]], b = mesh.vertices[c[(k + 1) % 3]],
               p = mesh.vertices[c[(k + 2) % 3]];
    const Vec3 e = b - a, d = p - a;
    const double len = norm(e);
    s.along[k] = dot(d, e) / len;
    s.left[k] = norm(cross(e, d)) / len;
  }
  return s;
}

std::array<Vec2, 3> place_root(const Mesh& mesh, int f, const FaceShape& shape) {
  const auto& c = mesh.faces[f];
  const double len = norm(mesh.vertices[c[1]] - mesh.vertices[c[0]]);
  std::array<Vec2, 3> p{Vec2{0, 0}, Vec2{len, 0}, Vec2{}};
  p[2] = place_third(p[0], p[1], shape.along[0], shape.left[0]);
  return p;
}

namespace {

Vec3 random_direction(Random& rng) {
  // Uniform on the sphere: z uniform in [-1, 1], angle uniform.
  const double z = 2 * rng.uniform() - 1;
  const double phi = 2 * M_PI * rng.uniform();
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// A dual edge between faces `face` and `other`, weighted: spanning trees prefer light links.
struct DualEdge {
  double weight;
  int face, other;
};

// Minimum spanning tree of the dual graph over `edges` (stable order for equal weights), as a
// parent array hanging from a root drawn from `rng`.
std::vector<int> spanning_tree(int nf, std::vector<DualEdge>& edges, Random& rng) {
  std::stable_sort(edges.begin(), edges.end(),
                   [](const DualEdge& x, const DualEdge& y) { return x.weight < y.weight; });
  UnionFind sets(nf);
  std::vector<std::vector<int>> tree(nf);
  int linked = 0;
  for (const DualEdge& e : edges)
    if (sets.unite(e.face, e.other)) {
      tree[e.face].push_back(e.other);
      tree[e.other].push_back(e.face);
      ++linked;
    }
  if (linked != nf - 1)
    throw InvalidInputException("the mesh is not connected across edges (" +
                                std::to_string(nf - linked) + " pieces); it cannot be one net");

  std::vector<int> parent(nf, -2);
  const int root = static_cast<int>(rng.below(nf));
  parent[root] = -1;
  std::vector<int> stack{root};
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    for (int q : tree[f])
      if (parent[q] == -2) {
        parent[q] = f;
        stack.push_back(q);
      }
  }
  return parent;
}

}  // namespace

std::vector<int> steepest_edge_tree(const Mesh& mesh, const DualGraph& graph, std::uint64_t seed) {
  const int nf = static_cast<int>(mesh.faces.size());
  const int nv = static_cast<int>(mesh.vertices.size());
  if (nf == 0) throw InvalidInputException("the mesh has no faces");
  Random rng(seed);
  const Vec3 c = random_direction(rng);

  // Steepest upward edge of every vertex (the highest vertex's is ignored).
  int highest = 0;
  for (int v = 1; v < nv; ++v)
    if (dot(c, mesh.vertices[v]) > dot(c, mesh.vertices[highest])) highest = v;
  std::vector<int> steepest(nv, -1);
  std::vector<double> slope(nv, -std::numeric_limits<double>::infinity());
  for (const auto& face : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const int v = face[k], w = face[(k + 1) % 3];
      const Vec3 d = mesh.vertices[w] - mesh.vertices[v];
      const double s = dot(c, d) / norm(d);
      if (s > slope[v]) slope[v] = s, steepest[v] = w;
      if (-s > slope[w]) slope[w] = -s, steepest[w] = v;
    }
  std::unordered_set<std::uint64_t> cuts;
  for (int v = 0; v < nv; ++v)
    if (v != highest && steepest[v] >= 0)
      cuts.insert(half_edge_key(std::min(v, steepest[v]), std::max(v, steepest[v])));

  // Dual edges (f, k) with f < neighbour, weighted: preferred cuts last, then by steepness.
  std::vector<DualEdge> edges;
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int q = graph.neighbour[f][k];
      if (q < f) continue;
      const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
      const Vec3 d = mesh.vertices[b] - mesh.vertices[a];
      const bool cut = cuts.count(half_edge_key(std::min(a, b), std::max(a, b))) != 0;
      edges.push_back({(cut ? 2.0 : 0.0) + std::abs(dot(c, d)) / norm(d), f, q});
    }
  return spanning_tree(nf, edges, rng);
}

std::vector<int> min_perimeter_tree(const Mesh& mesh, const DualGraph& graph, std::uint64_t seed) {
  const int nf = static_cast<int>(mesh.faces.size());
  if (nf == 0) throw InvalidInputException("the mesh has no faces");
  Random rng(seed);
  std::vector<DualEdge> edges;
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int q = graph.neighbour[f][k];
      if (q < f) continue;
      const Vec3 d = mesh.vertices[mesh.faces[f][(k + 1) % 3]] - mesh.vertices[mesh.faces[f][k]];
      edges.push_back({-norm(d), f, q});  // longest links first: the cut edges are the shortest
    }
  return spanning_tree(nf, edges, rng);
}

}  // namespace papernet
