#include "core/mesh/dual_graph.h"

#include <string>
#include <unordered_map>

#include "core/errors.h"

namespace papernet {

std::vector<char> boundary_vertices(const Mesh& mesh, const DualGraph& graph) {
  std::vector<char> out(mesh.vertices.size(), 0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      if (graph.neighbour[f][k] < 0) out[mesh.faces[f][k]] = out[mesh.faces[f][(k + 1) % 3]] = 1;
  return out;
}

std::size_t DualGraph::edge_count() const {
  std::size_t twice = 0;
  for (const auto& n : neighbour)
    for (int q : n) twice += q >= 0 ? 1 : 0;
  return twice / 2;
}

bool DualGraph::is_tree() const {
  return !neighbour.empty() && edge_count() + 1 == neighbour.size() && component_count() == 1;
}

std::size_t DualGraph::component_count() const {
  const int n = static_cast<int>(neighbour.size());
  std::vector<char> seen(n, 0);
  std::vector<int> stack;
  std::size_t components = 0;
  for (int s = 0; s < n; ++s) {
    if (seen[s]) continue;
    ++components;
    seen[s] = 1;
    stack.push_back(s);
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int q : neighbour[f])
        if (q >= 0 && !seen[q]) {
          seen[q] = 1;
          stack.push_back(q);
        }
    }
  }
  return components;
}

DualGraph build_dual_graph(const Mesh& mesh) {
  const int nf = static_cast<int>(mesh.faces.size());
  const int nv = static_cast<int>(mesh.vertices.size());
  std::unordered_map<std::uint64_t, int> half_edges;  // a->b  ->  3 * face + edge
  half_edges.reserve(3 * mesh.faces.size());
  for (int f = 0; f < nf; ++f) {
    const auto& c = mesh.faces[f];
    for (int k = 0; k < 3; ++k) {
      if (c[k] < 0 || c[k] >= nv)
        throw InvalidInputException("face " + std::to_string(f) + " uses vertex " +
                                    std::to_string(c[k]) + ", which does not exist");
      if (c[k] == c[(k + 1) % 3])
        throw InvalidInputException("face " + std::to_string(f) + " repeats vertex " +
                                    std::to_string(c[k]));
    }
    for (int k = 0; k < 3; ++k) {
      const int a = c[k], b = c[(k + 1) % 3];
      const auto [it, inserted] = half_edges.emplace(half_edge_key(a, b), 3 * f + k);
      if (!inserted)
        throw InvalidInputException(
            "edge " + std::to_string(a) + "-" + std::to_string(b) + " of face " +
            std::to_string(f) + " is also used in the same direction by face " +
            std::to_string(it->second / 3) + " (non-manifold or inconsistently oriented)");
    }
  }
  DualGraph graph;
  graph.neighbour.assign(nf, {-1, -1, -1});
  graph.neighbour_edge.assign(nf, {-1, -1, -1});
  for (int f = 0; f < nf; ++f) {
    const auto& c = mesh.faces[f];
    for (int k = 0; k < 3; ++k) {
      const auto it = half_edges.find(half_edge_key(c[(k + 1) % 3], c[k]));
      if (it == half_edges.end()) continue;
      graph.neighbour[f][k] = it->second / 3;
      graph.neighbour_edge[f][k] = static_cast<std::int8_t>(it->second % 3);
    }
  }
  return graph;
}

}  // namespace papernet
