#include "core/mesh/decimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/io/load.h"
#include "core/mesh/hausdorff.h"
#include "core/mesh/progressive_mesh.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

Mesh octahedron() {
  Mesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
             {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

// An axis-aligned cube of side 2 whose every side is an n x n grid of quads split in two.
Mesh subdivided_cube(int n) {
  Mesh m;
  auto vertex = [&](Vec3 p) {
    for (std::size_t i = 0; i < m.vertices.size(); ++i)
      if (m.vertices[i] == p) return static_cast<int>(i);
    m.vertices.push_back(p);
    return static_cast<int>(m.vertices.size() - 1);
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto at = [&](int a, int b) {
            const double u = -1 + 2.0 * a / n, v = -1 + 2.0 * b / n;
            if (axis == 0) return Vec3{double(sign), u, v};
            if (axis == 1) return Vec3{v, double(sign), u};
            return Vec3{u, v, double(sign)};
          };
          int a = vertex(at(i, j)), b = vertex(at(i + 1, j)), c = vertex(at(i + 1, j + 1)),
              d = vertex(at(i, j + 1));
          // (u, v) is right-handed with the outward axis only on the positive sides.
          if (sign < 0) std::swap(b, d);
          m.faces.push_back({a, b, c});
          m.faces.push_back({a, c, d});
        }
  return m;
}

std::string test_file(const char* name) { return papernet::test::test_data_dir() + "/" + name; }

bool bitwise_equal(const Mesh& a, const Mesh& b) {
  if (a.vertices.size() != b.vertices.size() || a.faces != b.faces) return false;
  return std::memcmp(a.vertices.data(), b.vertices.data(), a.vertices.size() * sizeof(Vec3)) == 0;
}

bool shares_edge(const Mesh& m, int f, int g, int a, int b) {
  auto has = [&](int face, int v) {
    const auto& c = m.faces[face];
    return c[0] == v || c[1] == v || c[2] == v;
  };
  return has(f, a) && has(f, b) && has(g, a) && has(g, b);
}

// Heights below 1e-6 of the longest edge count as degenerate, as in ProgressiveMesh.
bool degenerate(const Mesh& m, int f) {
  const auto& c = m.faces[f];
  const Vec3 a = m.vertices[c[0]], b = m.vertices[c[1]], d = m.vertices[c[2]];
  const double l = std::max({dot(b - a, b - a), dot(d - b, d - b), dot(a - d, a - d)});
  const Vec3 n = cross(b - a, d - a);
  return !(dot(n, n) > 1e-12 * l * l);
}

TEST(Decimate, CollapseTargetIsThePapersFormula) {
  EXPECT_EQ(collapse_target(2000, 0), std::size_t(std::llround(200 + std::sqrt(2000.0))));
  EXPECT_EQ(collapse_target(1000, 2), std::size_t(std::llround(100 + std::sqrt(1000.0) * 3)));
}

TEST(Decimate, OctahedronStopsAtATetrahedron) {
  Progress progress;
  for (CollapseStrategy s : {CollapseStrategy::QQ, CollapseStrategy::SEMP, CollapseStrategy::SEQ}) {
    ProgressiveMesh pm = decimate(octahedron(), {s, 1}, progress);
    EXPECT_EQ(pm.face_count(), 4u) << collapse_strategy_name(s);
    EXPECT_EQ(pm.vertex_count(), 4u);
    EXPECT_NO_THROW(ProgressiveMesh(pm.compact()));  // still a closed manifold
    while (pm.splits_left() > 0) pm.split();
    EXPECT_TRUE(bitwise_equal(pm.mesh(), octahedron()));
  }
}

TEST(Decimate, LinkConditionAndFlipsAreRefused) {
  ProgressiveMesh pm(octahedron());
  // Vertex 4's collapse into 5 crosses the octahedron (they are not neighbours).
  EXPECT_FALSE(pm.can_collapse(4, 5, {0, 0, 0}));
  // Moving the kept vertex through the opposite side flips faces.
  EXPECT_FALSE(pm.can_collapse(4, 0, {-3, 0, 0}));
  EXPECT_TRUE(pm.can_collapse(4, 0, {0.5, 0, 0.5}));
  pm.collapse(4, 0, {0.5, 0, 0.5});
  EXPECT_FALSE(pm.can_collapse(5, 0, {0.4, 0, 0}));  // would fold the mesh onto itself
  // Now 0, 1 and 5 form the equator of a triangular bipyramid: an equator edge has a third
  // common neighbour, a pole-equator edge does not.
  EXPECT_FALSE(pm.can_collapse(5, 1, {-0.5, 0, -0.5}));
  EXPECT_TRUE(pm.can_collapse(5, 2, pm.mesh().vertices[2]));
  pm.collapse(5, 2, pm.mesh().vertices[2]);
  EXPECT_EQ(pm.face_count(), 4u);
  // A tetrahedron cannot lose an edge.
  for (int v : {0, 1, 2, 3})
    for (int w : {0, 1, 2, 3}) EXPECT_FALSE(pm.can_collapse(v, w, pm.mesh().vertices[w]));
  EXPECT_THROW(pm.collapse(1, 2, {0, 0, 0}), TopologyException);
}

TEST(Decimate, BadInputIsNamed) {
  Mesh m = octahedron();
  m.faces[0] = {0, 4, 2};  // flipped: (0,4) and (4,2) now run the same way as neighbours
  EXPECT_THROW(ProgressiveMesh{m}, InvalidInputException);
  m = octahedron();
  m.faces.push_back({0, 2, 4});
  EXPECT_THROW(ProgressiveMesh{m}, InvalidInputException);
  m = octahedron();
  m.faces[0] = {0, 0, 4};
  EXPECT_THROW(ProgressiveMesh{m}, InvalidInputException);
  // Two octahedra sharing vertex 0 only: a non-manifold vertex.
  m = octahedron();
  const Mesh o = octahedron();
  const int base = static_cast<int>(m.vertices.size());
  for (Vec3 p : o.vertices) m.vertices.push_back(Vec3{p.x + 2, p.y, p.z});
  for (auto f : o.faces) {
    for (int& c : f) c = c == 1 ? 0 : c + base;
    m.faces.push_back(f);
  }
  m.vertices[base + 1] = m.vertices[0];
  EXPECT_THROW(ProgressiveMesh{m}, InvalidInputException);
}

TEST(Decimate, QuadricPlacementKeepsACubeExactly) {
  const Mesh cube = subdivided_cube(6);
  Progress progress;
  ProgressiveMesh qq = decimate(cube, {CollapseStrategy::QQ, 12}, progress);
  ProgressiveMesh semp = decimate(cube, {CollapseStrategy::SEMP, 12}, progress);
  EXPECT_LT(qq.face_count(), cube.faces.size() / 4);
  EXPECT_LT(semp.face_count(), cube.faces.size() / 4);
  // Quadric-optimal placement keeps corners and flat sides where they are (no sampled point
  // moved)...
  HausdorffOptions quick;
  quick.max_refinements = 20000;
  EXPECT_LT(hausdorff_distance(cube, qq.compact(), quick).distance, 1e-12);
  // ...midpoints cut corners.
  EXPECT_GT(hausdorff_distance(cube, semp.compact(), quick).distance, 1e-3);
}

struct Case {
  const char* file;
  int genus, boundaries;
};

class DecimateRoundTrip : public testing::TestWithParam<CollapseStrategy> {};

TEST_P(DecimateRoundTrip, SplittingEverythingRestoresTheInputExactly) {
  const Case cases[] = {{"sample.obj", 0, 0},           {"reference.obj", 0, 2},
                        {"mirror.ply", 1, 0},           {"thingi10k_65004.stl", 2, 0},
                        {"thingi10k_134617.stl", 0, 1}, {"Duck.glb", 0, 0}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const Mesh input = load_mesh_file(test_file(c.file)).mesh;
    ASSERT_FALSE(input.faces.empty());
    Progress progress;
    ProgressiveMesh pm = decimate(input, {GetParam(), 0}, progress);
    EXPECT_EQ(pm.genus(), c.genus);
    EXPECT_EQ(pm.boundary_loops(), c.boundaries);
    const std::size_t target = collapse_target(input.faces.size(), c.genus);
    EXPECT_LE(pm.face_count(), target);
    EXPECT_GE(pm.face_count() + 2, target);
    {
      ProgressiveMesh coarse(pm.compact());  // throws unless manifold and oriented
      EXPECT_EQ(coarse.genus(), c.genus);
      EXPECT_EQ(coarse.boundary_loops(), c.boundaries);
    }
    const std::size_t steps = pm.splits_left();
    std::size_t step = 0, wings = 0;
    while (pm.splits_left() > 0) {
      const VertexSplit& next = pm.next_split();
      // Wing faces are neighbours across (moved, w) before the split.
      for (const SplitFace& nf : next.new_faces) {
        const int w = nf.corners[0] != next.vertex && nf.corners[0] != next.moved   ? nf.corners[0]
                      : nf.corners[1] != next.vertex && nf.corners[1] != next.moved ? nf.corners[1]
                                                                                    : nf.corners[2];
        if (nf.wing[0] >= 0 && nf.wing[1] >= 0) {
          ++wings;
          ASSERT_TRUE(pm.face_alive(nf.wing[0]) && pm.face_alive(nf.wing[1]));
          ASSERT_TRUE(shares_edge(pm.mesh(), nf.wing[0], nf.wing[1], next.moved, w));
        }
      }
      const VertexSplit s = pm.split();
      ASSERT_EQ(pm.mesh().vertices[s.moved], s.moved_to);
      for (int f : s.reshaped) ASSERT_FALSE(degenerate(pm.mesh(), f)) << "face " << f;
      for (const SplitFace& nf : s.new_faces) {
        ASSERT_FALSE(degenerate(pm.mesh(), nf.face));
        ASSERT_EQ(pm.mesh().faces[nf.face], nf.corners);
      }
      if (++step % (steps / 8 + 1) == 0) {
        ASSERT_NO_THROW(ProgressiveMesh(pm.compact()));
      }
    }
    EXPECT_GT(wings, steps);
    EXPECT_EQ(pm.face_count(), input.faces.size());
    EXPECT_TRUE(bitwise_equal(pm.mesh(), input));
  }
}

INSTANTIATE_TEST_SUITE_P(Strategies, DecimateRoundTrip,
                         testing::Values(CollapseStrategy::QQ, CollapseStrategy::SEMP,
                                         CollapseStrategy::SEQ),
                         [](const auto& info) { return collapse_strategy_name(info.param); });

TEST(Decimate, QuadricsApproximateBetterThanMidpoints) {
  const Mesh input = load_mesh_file(test_file("sample.obj")).mesh;
  Progress progress;
  const double qq =
      hausdorff_distance(input, decimate(input, {CollapseStrategy::QQ, 0}, progress).compact())
          .distance;
  const double semp =
      hausdorff_distance(input, decimate(input, {CollapseStrategy::SEMP, 0}, progress).compact())
          .distance;
  EXPECT_LT(qq, semp);
}

// A flat 3 x 3 grid of vertices (i + 3j at (i, j, 0)), each quad split along its (i+1, j)-(i, j+1)
// diagonal: vertex 4 is the only interior vertex.
Mesh flat_grid() {
  Mesh m;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) m.vertices.push_back({double(i), double(j), 0});
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = i + 3 * j, b = a + 1, c = a + 4, d = a + 3;
      m.faces.push_back({a, b, d});
      m.faces.push_back({b, c, d});
    }
  return m;
}

TEST(Decimate, InteriorEdgeBetweenBoundaryVerticesIsRefused) {
  ProgressiveMesh pm(flat_grid());
  // (1, 3) is an interior edge whose ends are both on the border: collapsing it would pinch the
  // sheet (the link condition alone allows it, common neighbours 0 and 4).
  EXPECT_FALSE(pm.can_collapse(1, 3, pm.mesh().vertices[3]));
  // The interior vertex 4 may go into the border vertex 1.
  EXPECT_TRUE(pm.can_collapse(4, 1, pm.mesh().vertices[1]));
}

TEST(Decimate, TryCollapseAppliesOnlyLegalCollapses) {
  ProgressiveMesh pm(octahedron());
  EXPECT_FALSE(pm.try_collapse(4, 5, {0, 0, 0}));   // not neighbours
  EXPECT_FALSE(pm.try_collapse(4, 0, {-3, 0, 0}));  // flips faces
  EXPECT_EQ(pm.splits_left(), 0u);
  EXPECT_EQ(pm.face_count(), 8u);
  EXPECT_TRUE(bitwise_equal(pm.mesh(), octahedron()));
  EXPECT_TRUE(pm.try_collapse(4, 0, {0.5, 0, 0.5}));
  EXPECT_EQ(pm.splits_left(), 1u);
  EXPECT_EQ(pm.face_count(), 6u);
  EXPECT_FALSE(pm.vertex_alive(4));
}

TEST(Decimate, ReusedEvaluationsGiveTheSameCollapses) {
  // Closed, open (5 boundary loops), genus 2 and CAD-like flat sides, every strategy.
  const char* files[] = {"trimesh__ballA.obj", "draco__bun_zipper.obj", "thingi10k__472042.obj",
                         "trimesh__ADIS16480.obj"};
  const std::filesystem::path dir =
      std::filesystem::path(papernet::test::shared_data_dir()) / "bench/2000";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "needs ../shared/data: " << dir;
  for (const char* file : files)
    for (CollapseStrategy s :
         {CollapseStrategy::QQ, CollapseStrategy::SEMP, CollapseStrategy::SEQ}) {
      SCOPED_TRACE(std::string(file) + " " + collapse_strategy_name(s));
      const Mesh input = load_mesh_file((dir / file).string()).mesh;
      Progress progress;
      ProgressiveMesh reused = decimate(input, {s, 0, true}, progress);
      ProgressiveMesh fresh = decimate(input, {s, 0, false}, progress);
      ASSERT_EQ(reused.splits_left(), fresh.splits_left());
      EXPECT_GT(reused.splits_left(), 100u);  // a real run, not an empty one
      EXPECT_TRUE(bitwise_equal(reused.mesh(), fresh.mesh()));
      while (reused.splits_left() > 0) {
        const VertexSplit a = reused.split(), b = fresh.split();
        ASSERT_EQ(a.vertex, b.vertex);
        ASSERT_EQ(a.moved, b.moved);
        ASSERT_TRUE(std::memcmp(&a.moved_from, &b.moved_from, sizeof(Vec3)) == 0);
        ASSERT_EQ(a.new_faces.size(), b.new_faces.size());
      }
    }
}

TEST(Decimate, BenchMeshesRoundTrip) {
  // Higher genus, several boundary loops, CAD-like flat sides.
  const Case cases[] = {{"thingi10k__472042.obj", 2, 0},
                        {"trimesh__ADIS16480.obj", 24, 0},
                        {"draco__bun_zipper.obj", 0, 5},
                        {"draco__cube_subd.obj", 0, 0}};
  const std::filesystem::path dir =
      std::filesystem::path(papernet::test::shared_data_dir()) / "bench/2000";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "needs ../shared/data: " << dir;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const Mesh input = load_mesh_file((dir / c.file).string()).mesh;
    Progress progress;
    ProgressiveMesh pm = decimate(input, {CollapseStrategy::QQ, 0}, progress);
    EXPECT_EQ(pm.genus(), c.genus);
    EXPECT_EQ(pm.boundary_loops(), c.boundaries);
    EXPECT_LE(pm.face_count(), collapse_target(input.faces.size(), c.genus));
    ASSERT_NO_THROW(ProgressiveMesh(pm.compact()));
    while (pm.splits_left() > 0) pm.split();
    EXPECT_TRUE(bitwise_equal(pm.mesh(), input));
  }
}

}  // namespace
}  // namespace papernet
