// Tendrils of sprawling pieces cut off (print/tendrils.h, cut_tendrils; docs/print.md, "Tendrils
// cut off to save a sheet"): each cut is the link whose cut most shrinks its piece's convex hull,
// found here by trying every link, and undo_tendril_cut undoes it.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "core/unfold/net_check.h"
#include "core/unfold/net_metrics.h"
#include "core/unfold/tabu.h"
#include "print/fit.h"
#include "print/layout.h"
#include "print/tendrils.h"
#include "tests/support/meshes.h"
#include "tests/support/polygons.h"

namespace papernet {
namespace {

// The area of the convex hull of the corners of `faces`' triangles in `net`.
double hull_area_of(const Net& net, const std::vector<int>& faces) {
  std::vector<Vec2> points;
  for (int f : faces) points.insert(points.end(), net.points[f].begin(), net.points[f].end());
  return std::abs(test::signed_area(convex_hull(points)));
}

// The faces of `face`'s subtree in `net` (its own piece: links end at roots).
std::vector<int> subtree(const Net& net, int face) {
  std::vector<std::vector<int>> children(net.parent.size());
  for (std::size_t g = 0; g < net.parent.size(); ++g)
    if (net.parent[g] >= 0)
      children[static_cast<std::size_t>(net.parent[g])].push_back(static_cast<int>(g));
  std::vector<int> out{face};
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int c : children[static_cast<std::size_t>(out[i])]) out.push_back(c);
  return out;
}

// By trying every link: the most that cutting one shrinks its piece's hull (the piece's hull
// area less those of the two pieces it makes).
double most_shrink(const FitPieces& pieces) {
  double most = 0;
  for (std::size_t f = 0; f < pieces.piece.size(); ++f) {
    if (pieces.net.parent[f] < 0) continue;
    std::vector<int> whole;
    for (std::size_t g = 0; g < pieces.piece.size(); ++g)
      if (pieces.piece[g] == pieces.piece[f]) whole.push_back(static_cast<int>(g));
    const std::vector<int> below = subtree(pieces.net, static_cast<int>(f));
    const std::set<int> cut(below.begin(), below.end());
    std::vector<int> rest;
    for (int g : whole)
      if (!cut.count(g)) rest.push_back(g);
    most = std::max(most, hull_area_of(pieces.net, whole) - hull_area_of(pieces.net, below) -
                              hull_area_of(pieces.net, rest));
  }
  return most;
}

// Whether each piece of `pieces` is one tree of its links: one root, every other face hanging
// from a face of its own piece, and the count of pieces right.
void expect_one_tree_each(const FitPieces& pieces) {
  std::vector<int> roots(static_cast<std::size_t>(pieces.pieces), 0);
  for (std::size_t f = 0; f < pieces.piece.size(); ++f) {
    ASSERT_GE(pieces.piece[f], 0);
    ASSERT_LT(pieces.piece[f], pieces.pieces);
    const int up = pieces.net.parent[f];
    if (up < 0)
      ++roots[static_cast<std::size_t>(pieces.piece[f])];
    else
      EXPECT_EQ(pieces.piece[static_cast<std::size_t>(up)], pieces.piece[f]) << "face " << f;
  }
  for (int p = 0; p < pieces.pieces; ++p) EXPECT_EQ(roots[static_cast<std::size_t>(p)], 1);
}

TEST(Tendrils, EachCutShrinksAPiecesHullTheMostAndCanBeUndone) {
  Mesh mesh;
  for (auto& [name, m] : test::test_data_meshes())
    if (name == "thingi10k_65004.stl") mesh = m;
  ASSERT_FALSE(mesh.faces.empty()) << "tests/data has no thingi10k_65004.stl";
  Progress quiet;
  TabuOptions options;
  options.time_limit_seconds = 600;  // against a hang only
  const Net net = unfold_tabu(mesh, options, quiet).net;
  const double scale = print_scale(mesh, {});  // 200 mm
  const std::vector<int> one(mesh.faces.size(), 0);
  const FitPieces cut = cut_to_fit(net, one, scale, {{176, 263}, {}}, "A4", 200);
  ASSERT_GT(cut.pieces, 1);

  FitPieces pieces = cut;
  std::vector<TendrilCut> made;
  for (int k = 0; k < 3; ++k) {
    const double expected = most_shrink(pieces);
    const FitPieces before = pieces;
    const std::vector<TendrilCut> one_cut = cut_tendrils(pieces, 1);
    ASSERT_EQ(one_cut.size(), 1u) << "no link of a sprawling net shrinks its hull";
    const TendrilCut c = one_cut[0];
    EXPECT_EQ(c.parent, before.net.parent[c.face]);
    EXPECT_EQ(pieces.net.parent[c.face], -1);
    EXPECT_EQ(pieces.pieces, before.pieces + 1);
    EXPECT_EQ(pieces.cut_links, before.cut_links + 1);
    EXPECT_EQ(pieces.net.points, before.net.points);  // each piece keeps its frame
    // The cut's shrink is the most of any link's.
    std::vector<int> whole;
    for (std::size_t g = 0; g < before.piece.size(); ++g)
      if (before.piece[g] == before.piece[c.face]) whole.push_back(static_cast<int>(g));
    const std::vector<int> below = subtree(pieces.net, c.face);
    const std::set<int> off(below.begin(), below.end());
    std::vector<int> rest;
    for (int g : whole)
      if (!off.count(g)) rest.push_back(g);
    const double shrink = hull_area_of(before.net, whole) - hull_area_of(before.net, below) -
                          hull_area_of(before.net, rest);
    EXPECT_GT(shrink, 0);
    EXPECT_NEAR(shrink, expected, 1e-9 * hull_area_of(before.net, whole));
    expect_one_tree_each(pieces);
    const NetCheckReport check = check_pieces(mesh, pieces.net, pieces.piece);
    EXPECT_TRUE(check.ok()) << check.summary();
    made.push_back(c);
  }
  // Glued back, the last first: the pieces cut_to_fit made, each face with the same others.
  for (auto it = made.rbegin(); it != made.rend(); ++it) undo_tendril_cut(pieces, *it);
  EXPECT_EQ(pieces.net.parent, cut.net.parent);
  EXPECT_EQ(pieces.pieces, cut.pieces);
  EXPECT_EQ(pieces.cut_links, cut.cut_links);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (std::size_t g = f + 1; g < mesh.faces.size(); g += 37)
      EXPECT_EQ(pieces.piece[f] == pieces.piece[g], cut.piece[f] == cut.piece[g]);
  expect_one_tree_each(pieces);
}

}  // namespace
}  // namespace papernet
