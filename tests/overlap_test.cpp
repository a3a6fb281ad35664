#include "core/overlap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace papernet {
namespace {

constexpr double kTol = 1e-9;

TEST(TrianglesOverlap, GluedAlongAnEdgeDoesNotCount) {
  const Triangle2 a{Vec2{0, 0}, Vec2{1, 0}, Vec2{0, 1}};
  const Triangle2 b{Vec2{1, 0}, Vec2{0, 0}, Vec2{0.5, -1}};  // far side of edge 0-1
  EXPECT_FALSE(triangles_overlap(a, b, kTol));
  EXPECT_FALSE(triangles_overlap(a, b, 0));  // exact even without tolerance
}

TEST(TrianglesOverlap, TouchingAtAVertexDoesNotCount) {
  const Triangle2 a{Vec2{0, 0}, Vec2{1, 0}, Vec2{0, 1}};
  const Triangle2 b{Vec2{1, 0}, Vec2{2, 0}, Vec2{2, 1}};
  EXPECT_FALSE(triangles_overlap(a, b, kTol));
  // Same, with the shared corner off by rounding.
  const Triangle2 c{Vec2{1 + 1e-15, 1e-15}, Vec2{2, 0}, Vec2{2, 1}};
  EXPECT_FALSE(triangles_overlap(a, c, kTol));
}

TEST(TrianglesOverlap, CollinearEdgesMeetingAtAVertexDoNotCount) {
  // b continues a's edge 1->2 beyond corner 2, on the same side: they touch only at (0, 1).
  const Triangle2 a{Vec2{0, 0}, Vec2{1, 0}, Vec2{0, 1}};
  const Triangle2 b{Vec2{0, 1}, Vec2{-1, 2}, Vec2{-2, 2.5}};
  EXPECT_FALSE(triangles_overlap(a, b, kTol));
}

TEST(TrianglesOverlap, CrossingAndContainedTrianglesCount) {
  const Triangle2 a{Vec2{0, 0}, Vec2{1, 0}, Vec2{0, 1}};
  const Triangle2 crossing{Vec2{0.2, 0.2}, Vec2{2, 0.2}, Vec2{0.2, 2}};
  const Triangle2 inside{Vec2{0.1, 0.1}, Vec2{0.3, 0.1}, Vec2{0.1, 0.3}};
  const Triangle2 star{Vec2{0.25, -0.5}, Vec2{0.75, 1}, Vec2{-0.25, 0.5}};  // no corner inside
  EXPECT_TRUE(triangles_overlap(a, crossing, kTol));
  EXPECT_TRUE(triangles_overlap(a, inside, kTol));
  EXPECT_TRUE(triangles_overlap(inside, a, kTol));
  EXPECT_TRUE(triangles_overlap(a, star, kTol));
}

TEST(TrianglesOverlap, OverlapThinnerThanTheToleranceIsIgnored) {
  const Triangle2 a{Vec2{0, 0}, Vec2{1, 0}, Vec2{0, 1}};
  const Triangle2 b{Vec2{1, 1e-12}, Vec2{0, 1e-12}, Vec2{0.5, -1}};  // 1e-12 into a
  EXPECT_FALSE(triangles_overlap(a, b, kTol));
  EXPECT_TRUE(triangles_overlap(a, b, 0));
}

TEST(OverlapGrid, FindsInsertedFacesAndForgetsRemovedOnes) {
  OverlapGrid grid;
  grid.reset(1.0);
  grid.insert(0, {{0.1, 0.1}, {0.9, 0.9}});
  grid.insert(1, {{5.1, 5.1}, {5.9, 5.9}});
  grid.insert(2, {{-100, -100}, {100, 100}});  // far larger than a cell
  const auto found = [&](const Box2& box) {
    std::vector<int> faces;
    grid.query(box, [&](int f) { faces.push_back(f); });
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    return faces;
  };
  EXPECT_EQ(found({{0.5, 0.5}, {0.6, 0.6}}), (std::vector<int>{0, 2}));
  EXPECT_EQ(found({{5.5, 5.5}, {5.6, 5.6}}), (std::vector<int>{1, 2}));
  grid.remove(2);
  grid.remove(0);
  EXPECT_FALSE(grid.contains(0));
  EXPECT_TRUE(grid.contains(1));
  EXPECT_EQ(found({{0.5, 0.5}, {0.6, 0.6}}), std::vector<int>{});
  EXPECT_EQ(found({{-1, -1}, {10, 10}}), std::vector<int>{1});
}

}  // namespace
}  // namespace papernet
