#include "core/unfold/overlap.h"
#include "core/unfold/overlap_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/load.h"
#include "core/unfold/unfolding.h"
#include "tests/support/paths.h"

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

// The faces a grid query visits, each once, in order.
std::vector<int> faces_found(const OverlapGrid& grid, const Box2& box) {
  std::vector<int> faces;
  grid.query(box, [&](int f) { faces.push_back(f); });
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

TEST(OverlapGrid, FindsInsertedFacesAndForgetsRemovedOnes) {
  OverlapGrid grid;
  grid.reset(1.0);
  grid.insert(0, {{0.1, 0.1}, {0.9, 0.9}});
  grid.insert(1, {{5.1, 5.1}, {5.9, 5.9}});
  grid.insert(2, {{-100, -100}, {100, 100}});  // far larger than a cell
  const auto found = [&](const Box2& box) { return faces_found(grid, box); };
  EXPECT_EQ(found({{0.5, 0.5}, {0.6, 0.6}}), (std::vector<int>{0, 2}));
  EXPECT_EQ(found({{5.5, 5.5}, {5.6, 5.6}}), (std::vector<int>{1, 2}));
  grid.remove(2);
  grid.remove(0);
  EXPECT_FALSE(grid.contains(0));
  EXPECT_TRUE(grid.contains(1));
  EXPECT_EQ(found({{0.5, 0.5}, {0.6, 0.6}}), std::vector<int>{});
  EXPECT_EQ(found({{-1, -1}, {10, 10}}), std::vector<int>{1});
}

// A level whose last face is removed is skipped by queries until a face lands there again; points
// on cell boundaries and inside cells of negative coordinates find the faces there.
TEST(OverlapGrid, EmptiedLevelsAndNegativeCellBoundaries) {
  OverlapGrid grid;
  grid.reset(1.0);
  const auto found = [&](const Box2& box) { return faces_found(grid, box); };
  grid.insert(0, {{-2, -2}, {-1, -1}});                           // finest level, cells -2..-1
  grid.insert(1, {{-40, -40}, {-20, -20}});                       // a coarser level
  EXPECT_EQ(found({{-1, -1}, {-1, -1}}), (std::vector<int>{0}));  // the corner, on a boundary
  EXPECT_EQ(found({{-1.75, -1.25}, {-1.75, -1.25}}), (std::vector<int>{0}));
  grid.remove(0);  // the finest level is empty now
  EXPECT_EQ(found({{-30, -30}, {-1, -1}}), std::vector<int>{1});
  grid.insert(2, {{-1.5, -1.5}, {-1.25, -1.25}});  // and used again
  EXPECT_EQ(found({{-1.3, -1.3}, {-1.3, -1.3}}), (std::vector<int>{2}));
  EXPECT_EQ(found({{-30, -30}, {-1, -1}}), (std::vector<int>{1, 2}));
  grid.remove(1);
  grid.remove(2);
  EXPECT_EQ(found({{-1e6, -1e6}, {1e6, 1e6}}), std::vector<int>{});
}

// Faces from 0.01 to 10,000 units wide land in different levels of the grid; a query must still
// return every face whose box meets the query box (checked against all pairs).
TEST(OverlapGrid, FindsEveryMeetingBoxAcrossSizes) {
  OverlapGrid grid;
  grid.reset(1.0);
  std::vector<Box2> boxes;
  std::uint64_t s = 12345;
  const auto next = [&s] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(s >> 11) / 9007199254740992.0;
  };
  for (int f = 0; f < 400; ++f) {
    const double size = std::pow(10.0, -2 + 6 * next());
    const Vec2 lo{-500 + 1000 * next(), -500 + 1000 * next()};
    boxes.push_back({lo, {lo.x + size, lo.y + size * next()}});
    grid.insert(f, boxes.back());
  }
  for (int f = 0; f < 400; f += 3) grid.remove(f);
  const auto meets = [](const Box2& a, const Box2& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y;
  };
  for (int f = 0; f < 400; ++f) {
    std::vector<char> seen(400, 0);
    grid.query(boxes[f], [&](int c) { seen[c] = 1; });
    for (int c = 0; c < 400; ++c) {
      if (c % 3 == 0) {
        EXPECT_FALSE(seen[c]) << "removed face " << c << " returned";
      } else if (meets(boxes[f], boxes[c])) {
        EXPECT_TRUE(seen[c]) << "face " << c << " missed by the query of " << f;
      }
    }
  }
}

// A net that is one long strip of slivers (the Twin plate: faces 9,000 units long and a hundredth
// wide, all in a strip 12 units high): such faces go into the grid's tree, whose query returns
// each face whose box meets the query box exactly once, and no other. Faces are moved (removed
// and inserted elsewhere) as the Tabu Unfolder does.
TEST(OverlapGrid, StripOfSliversReturnsEachMeetingBoxOnce) {
  OverlapGrid grid;
  grid.reset(1.0);
  std::uint64_t s = 777;
  const auto next = [&s] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(s >> 11) / 9007199254740992.0;
  };
  const auto sliver = [&] {
    const double x = 9000 * next(), y = 12 * next();
    return Box2{{x, y}, {x + 100 + 8900 * next(), y + 0.01 + next()}};
  };
  constexpr int kFaces = 300;
  std::vector<Box2> boxes;
  for (int f = 0; f < kFaces; ++f) {
    boxes.push_back(f % 10 == 0 ? Box2{{9000 * next(), 12 * next()}, {0, 0}} : sliver());
    if (f % 10 == 0) boxes[f].hi = {boxes[f].lo.x + 0.5, boxes[f].lo.y + 0.5};  // compact ones
    grid.insert(f, boxes[f]);
  }
  for (int f = 0; f < kFaces; f += 4) {  // moves
    grid.remove(f);
    boxes[f] = sliver();
    grid.insert(f, boxes[f]);
  }
  const auto meets = [](const Box2& a, const Box2& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y;
  };
  for (int f = 0; f < kFaces; ++f) {
    std::vector<int> count(kFaces, 0);
    grid.query(boxes[f], [&](int c) { ++count[c]; });
    for (int c = 0; c < kFaces; ++c) {
      if (meets(boxes[f], boxes[c])) {
        EXPECT_GE(count[c], 1) << "face " << c << " missed by the query of " << f;
      } else if (c % 10 != 0) {
        EXPECT_EQ(count[c], 0) << "sliver " << c << " does not meet " << f;
      }
      if (c % 10 != 0) {
        EXPECT_LE(count[c], 1) << "sliver " << c << " returned twice";
      }
    }
  }
  for (int f = 0; f < kFaces; ++f) grid.remove(f);
  int left = 0;
  grid.query({{-1e6, -1e6}, {1e6, 1e6}}, [&](int) { ++left; });
  EXPECT_EQ(left, 0);
}

// Real nets (steepest-edge unfoldings of an organic mesh and of CAD parts of slivers, whose
// layouts overlap and whose glued neighbours' boxes touch exactly), with the finest cell at the
// median edge as Unfolding sets it: every face's box query finds every face whose box meets it
// (brute force over all pairs), also after a third of the faces moved by a rigid motion (remove,
// insert elsewhere) as the Tabu Unfolder's moves do and a seventh were removed, and for boxes
// grown to ten times their size. Removed faces are never returned.
TEST(OverlapGrid, RealNetsMatchBruteForce) {
  for (const char* name : {"c3d__spot", "thingi10k__79741", "trimesh__1002_tray_bottom"}) {
    SCOPED_TRACE(name);
    const std::filesystem::path file = std::filesystem::path(papernet::test::shared_data_dir()) /
                                       "bench" / "800" / (std::string(name) + ".obj");
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "needs ../shared/data: " << file.string();
    const Mesh mesh = load_mesh_file(file.string()).mesh;
    const Unfolding u = Unfolding::steepest_edge(mesh, 1);
    const int nf = static_cast<int>(u.face_count());
    OverlapGrid grid;
    grid.reset(median_edge_length(mesh));
    std::vector<Box2> boxes(nf);
    std::vector<char> in(nf, 1);
    for (int f = 0; f < nf; ++f) {
      boxes[f] = triangle_box(u.points(f));
      grid.insert(f, boxes[f]);
    }
    const auto meets = [](const Box2& a, const Box2& b) {
      return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y;
    };
    std::size_t pairs = 0;
    const auto check = [&](const Box2& box) {
      std::vector<char> seen(nf, 0);
      grid.query(box, [&](int c) { seen[c] = 1; });
      for (int c = 0; c < nf; ++c) {
        if (!in[c]) {
          ASSERT_FALSE(seen[c]) << "removed face " << c << " returned";
        } else if (meets(box, boxes[c])) {
          ASSERT_TRUE(seen[c]) << "face " << c << " missed";
          ++pairs;
        }
      }
    };
    for (int f = 0; f < nf; ++f) check(boxes[f]);
    EXPECT_GT(pairs, static_cast<std::size_t>(3 * nf));  // each face meets itself and neighbours
    // Move every third face: rotate its triangle by 0.3 rad about a corner of face 0.
    const Vec2 o = u.points(0)[0];
    const double c = std::cos(0.3), s = std::sin(0.3);
    for (int f = 0; f < nf; f += 3) {
      grid.remove(f);
      Triangle2 t = u.points(f);
      for (Vec2& p : t)
        p = {o.x + c * (p.x - o.x) - s * (p.y - o.y), o.y + s * (p.x - o.x) + c * (p.y - o.y)};
      boxes[f] = triangle_box(t);
      grid.insert(f, boxes[f]);
    }
    for (int f = 1; f < nf; f += 7) {
      grid.remove(f);
      in[f] = 0;
    }
    for (int f = 0; f < nf; ++f) check(boxes[f]);
    for (int f = 0; f < nf; f += 5) {
      const Box2& b = boxes[f];
      const Vec2 d{10 * (b.hi.x - b.lo.x), 10 * (b.hi.y - b.lo.y)};
      check({{b.lo.x - d.x, b.lo.y - d.y}, {b.hi.x + d.x, b.hi.y + d.y}});
    }
  }
}

// triangles_overlap_in_boxes (the test without its box check, for callers that checked the
// boxes) gives triangles_overlap's answer for every pair of faces whose boxes overlap in real
// steepest-edge nets (overlapping layouts, glued neighbours, CAD slivers), also with tolerance 0.
TEST(TrianglesOverlap, InBoxesAgreesOnRealNets) {
  for (const char* name : {"c3d__spot", "thingi10k__79741"}) {
    SCOPED_TRACE(name);
    const std::filesystem::path file = std::filesystem::path(papernet::test::shared_data_dir()) /
                                       "bench" / "800" / (std::string(name) + ".obj");
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "needs ../shared/data: " << file.string();
    const Unfolding u = Unfolding::steepest_edge(load_mesh_file(file.string()).mesh, 1);
    const int nf = static_cast<int>(u.face_count());
    std::size_t compared = 0, overlapping = 0;
    for (double tol : {u.tolerance(), 0.0})
      for (int a = 0; a < nf; ++a)
        for (int b = 0; b < nf; ++b) {
          if (!boxes_overlap(triangle_box(u.points(a)), triangle_box(u.points(b)), tol)) continue;
          const bool expected = triangles_overlap(u.points(a), u.points(b), tol);
          ASSERT_EQ(triangles_overlap_in_boxes(u.points(a), u.points(b), tol), expected)
              << "faces " << a << ", " << b;
          ++compared;
          overlapping += expected ? 1 : 0;
        }
    EXPECT_GT(compared, static_cast<std::size_t>(4 * nf));  // neighbours' boxes overlap
    EXPECT_GT(overlapping, 0u);  // steepest-edge nets of these meshes overlap
  }
}

}  // namespace
}  // namespace papernet
