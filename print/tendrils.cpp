// Tendrils of sprawling pieces cut off, to nest onto fewer sheets (print/tendrils.h, cut_tendrils).
#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/unfold/net_metrics.h"
#include "print/fit.h"
#include "print/tendrils.h"

namespace papernet {
namespace {

// The link whose cut most shrinks its piece's hull (the two pieces' hulls against the piece's):
// {face, gain}, face -1 when no cut shrinks it. Each face's subtree hull bottom-up from the
// leaves, and the hull of the rest of its piece top-down from the root, each from a few hulls.
struct BestCut {
  int face = -1;
  double gain = 0;
};

BestCut best_cut(const FitPieces& pieces) {
  const Net& net = pieces.net;
  const std::size_t n = net.parent.size();
  std::vector<std::vector<int>> children(n);
  std::vector<int> order;  // each face after its parent
  order.reserve(n);
  for (std::size_t f = 0; f < n; ++f) {
    if (net.parent[f] >= 0)
      children[static_cast<std::size_t>(net.parent[f])].push_back(static_cast<int>(f));
    else
      order.push_back(static_cast<int>(f));
  }
  for (std::size_t i = 0; i < order.size(); ++i)
    for (int c : children[static_cast<std::size_t>(order[i])]) order.push_back(c);
  // below[f]: the hull of f's subtree; rest[f]: of its piece without that subtree.
  std::vector<std::vector<Vec2>> below(n), rest(n);
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const auto f = static_cast<std::size_t>(*it);
    std::vector<Vec2> points(net.points[f].begin(), net.points[f].end());
    for (int c : children[f])
      points.insert(points.end(), below[static_cast<std::size_t>(c)].begin(),
                    below[static_cast<std::size_t>(c)].end());
    below[f] = convex_hull(std::move(points));
  }
  std::vector<int> root(n);
  for (int face : order) {
    const auto f = static_cast<std::size_t>(face);
    root[f] = net.parent[f] < 0 ? face : root[static_cast<std::size_t>(net.parent[f])];
  }
  BestCut best;
  for (int face : order) {
    const auto f = static_cast<std::size_t>(face);
    const int up = net.parent[f];
    if (up < 0) continue;
    const auto p = static_cast<std::size_t>(up);
    std::vector<Vec2> points(net.points[p].begin(), net.points[p].end());
    points.insert(points.end(), rest[p].begin(), rest[p].end());
    for (int s : children[p])
      if (s != face)
        points.insert(points.end(), below[static_cast<std::size_t>(s)].begin(),
                      below[static_cast<std::size_t>(s)].end());
    rest[f] = convex_hull(std::move(points));
    // The hull of the root's subtree is the whole piece's.
    const double gain = hull_area(below[static_cast<std::size_t>(root[f])]) - hull_area(below[f]) -
                        hull_area(rest[f]);
    if (gain > best.gain) best = {face, gain};
  }
  return best;
}

// Each face's piece from the trees of `pieces.net`: a piece for each root, in the roots' order
// by face, and the count of pieces.
void number_pieces_by_tree(FitPieces& pieces) {
  const std::vector<int>& parent = pieces.net.parent;
  const std::size_t n = parent.size();
  std::vector<std::vector<int>> children(n);
  std::vector<int> order;  // each face after its parent
  pieces.piece.assign(n, -1);
  pieces.pieces = 0;
  for (std::size_t f = 0; f < n; ++f) {
    if (parent[f] >= 0) {
      children[static_cast<std::size_t>(parent[f])].push_back(static_cast<int>(f));
    } else {
      order.push_back(static_cast<int>(f));
      pieces.piece[f] = pieces.pieces++;
    }
  }
  for (std::size_t i = 0; i < order.size(); ++i)
    for (int c : children[static_cast<std::size_t>(order[i])]) {
      pieces.piece[static_cast<std::size_t>(c)] = pieces.piece[static_cast<std::size_t>(order[i])];
      order.push_back(c);
    }
}

}  // namespace

std::vector<TendrilCut> cut_tendrils(FitPieces& pieces, int count) {
  std::vector<TendrilCut> cuts;
  for (int k = 0; k < count; ++k) {
    const BestCut cut = best_cut(pieces);
    if (cut.face < 0) break;
    const auto f = static_cast<std::size_t>(cut.face);
    cuts.push_back({cut.face, pieces.net.parent[f]});
    pieces.net.parent[f] = -1;
    ++pieces.cut_links;
    number_pieces_by_tree(pieces);
  }
  return cuts;
}

void undo_tendril_cut(FitPieces& pieces, const TendrilCut& cut) {
  pieces.net.parent[static_cast<std::size_t>(cut.face)] = cut.parent;
  --pieces.cut_links;
  number_pieces_by_tree(pieces);
}

}  // namespace papernet
