#include "print/build_order.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <unordered_map>

#include "core/mesh/dual_graph.h"

namespace papernet {

PieceGraph piece_graph(const Mesh& mesh, const std::vector<int>& piece) {
  int count = 0;
  for (int p : piece) count = std::max(count, p + 1);
  // Each mesh edge (its two vertices, either way round) and the faces on it. Not the dual graph
  // (core/mesh/dual_graph.h): that refuses faces oriented against each other, which a printed
  // net of a non-orientable part may have.
  std::unordered_map<std::uint64_t, std::array<int, 3>> faces_on;  // up to two faces, and a count
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
      auto& on = faces_on
                     .try_emplace(half_edge_key(std::min(a, b), std::max(a, b)),
                                  std::array<int, 3>{-1, -1, 0})
                     .first->second;
      if (on[2] < 2) on[on[2]] = f;
      ++on[2];
    }
  std::vector<std::map<int, int>> shared(static_cast<std::size_t>(count));
  for (const auto& [edge, on] : faces_on) {
    if (on[2] != 2 || piece[on[0]] == piece[on[1]]) continue;
    ++shared[piece[on[0]]][piece[on[1]]];
    ++shared[piece[on[1]]][piece[on[0]]];
  }
  PieceGraph out;
  out.joins.resize(shared.size());
  out.edges.resize(shared.size());
  for (std::size_t p = 0; p < shared.size(); ++p)
    for (const auto& [q, n] : shared[p]) {
      out.joins[p].push_back(q);
      out.edges[p].push_back(n);
    }
  return out;
}

std::vector<int> build_order(const PieceGraph& graph, const std::vector<double>& area) {
  const auto count = static_cast<int>(graph.joins.size());
  std::vector<int> order(static_cast<std::size_t>(count), -1);
  // Edges each piece shares with the pieces numbered so far.
  std::vector<int> to_built(static_cast<std::size_t>(count), 0);
  auto larger = [&](int a, int b) { return area[a] > area[b] || (area[a] == area[b] && a < b); };
  for (int next = 0; next < count; ++next) {
    int best = -1;
    for (int p = 0; p < count; ++p) {
      if (order[p] >= 0) continue;
      if (best < 0 || to_built[p] > to_built[best] ||
          (to_built[p] == to_built[best] && larger(p, best)))
        best = p;
    }
    order[best] = next;
    for (std::size_t i = 0; i < graph.joins[best].size(); ++i)
      to_built[graph.joins[best][i]] += graph.edges[best][i];
  }
  return order;
}

void renumber_pieces(std::vector<int>& piece, const std::vector<int>& order) {
  for (int& p : piece) p = order[p];
}

}  // namespace papernet
