#include "print/build_order.h"

#include <algorithm>
#include <map>

#include "core/mesh/dual_graph.h"

namespace papernet {

PieceGraph piece_graph(const Mesh& mesh, const std::vector<int>& piece) {
  int count = 0;
  for (int p : piece) count = std::max(count, p + 1);
  std::vector<std::map<int, int>> shared(static_cast<std::size_t>(count));
  const DualGraph dual = build_dual_graph(mesh);
  for (std::size_t f = 0; f < dual.neighbour.size(); ++f)
    for (const int g : dual.neighbour[f])
      if (g > static_cast<int>(f) && piece[f] != piece[g]) {
        ++shared[piece[f]][piece[g]];
        ++shared[piece[g]][piece[f]];
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
