// The build order of pieces (docs/print.md, "Build order"): each piece after one it glues to,
// whenever the piece graph allows.
#include <gtest/gtest.h>

#include "print/build_order.h"
#include "tests/support/meshes.h"

namespace papernet {
namespace {

PieceGraph graph_of(int count, const std::vector<std::array<int, 3>>& edges) {
  PieceGraph g;
  g.joins.resize(count);
  g.edges.resize(count);
  for (const auto& [a, b, n] : edges) {
    g.joins[a].push_back(b), g.edges[a].push_back(n);
    g.joins[b].push_back(a), g.edges[b].push_back(n);
  }
  return g;
}

// A chain 0 - 1 - 2 - 3 with 3 the largest: numbering starts there and walks the chain.
TEST(BuildOrder, StartsAtTheLargestPieceAndFollowsTheChain) {
  const PieceGraph g = graph_of(4, {{{0, 1, 1}}, {{1, 2, 1}}, {{2, 3, 1}}});
  EXPECT_EQ(build_order(g, {1, 2, 3, 10}), (std::vector<int>{3, 2, 1, 0}));
}

// Next comes the piece sharing the most edges with those numbered; a part of its own (4, 5)
// starts again from its largest piece once the first part is done.
TEST(BuildOrder, MostSharedEdgesFirstThenTheNextPart) {
  const PieceGraph g =
      graph_of(6, {{{0, 1, 1}}, {{0, 2, 3}}, {{1, 2, 1}}, {{3, 1, 2}}, {{4, 5, 1}}});
  // 0 largest; then 2 (3 edges to 0), then 1 (1 + 1), then 3, then 5 (larger than 4), then 4.
  EXPECT_EQ(build_order(g, {9, 5, 4, 3, 1, 2}), (std::vector<int>{0, 2, 1, 3, 5, 4}));
}

// The piece graph counts the mesh edges between faces of different pieces.
TEST(BuildOrder, PieceGraphCountsTheEdgesBetweenPieces) {
  const Mesh cube = test::cube();
  std::vector<int> piece(cube.faces.size(), 0);
  for (std::size_t f = 0; f < piece.size(); ++f) piece[f] = f < 6 ? 0 : 1;
  const PieceGraph g = piece_graph(cube, piece);
  ASSERT_EQ(g.joins.size(), 2u);
  ASSERT_EQ(g.joins[0], std::vector<int>{1});
  ASSERT_EQ(g.joins[1], std::vector<int>{0});
  EXPECT_EQ(g.edges[0], g.edges[1]);
  EXPECT_GT(g.edges[0][0], 0);
  std::vector<int> order = build_order(g, {1, 2});
  EXPECT_EQ(order, (std::vector<int>{1, 0}));
  renumber_pieces(piece, order);
  EXPECT_EQ(piece.front(), 1);
  EXPECT_EQ(piece.back(), 0);
}

}  // namespace
}  // namespace papernet
