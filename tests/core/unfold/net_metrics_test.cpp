#include "core/unfold/net_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/unfold/folds.h"
#include "tests/support/meshes.h"

namespace papernet {
namespace {

/// Axis-aligned box area and sides of the points rotated by `angle`.
struct Sweep {
  double area, w, h;
};
Sweep aabb(const std::vector<Vec2>& pts, double angle) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (Vec2 p : pts) {
    const Vec2 q = rotate(p, angle);
    x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
  }
  return {(x1 - x0) * (y1 - y0), x1 - x0, y1 - y0};
}

/// Independent minimum: a fine sweep of rotations over a quarter turn, refined around the best.
Sweep brute_force(const std::vector<Vec2>& pts) {
  Sweep best{1e300, 0, 0};
  double best_angle = 0;
  const int steps = 5000;
  for (int i = 0; i < steps; ++i) {
    const double a = 0.5 * std::numbers::pi * i / steps;
    const Sweep s = aabb(pts, a);
    if (s.area < best.area) best = s, best_angle = a;
  }
  for (double step = 1e-3; step > 1e-12; step *= 0.5)
    for (bool better = true; better;) {
      better = false;
      for (double a : {best_angle - step, best_angle + step})
        if (const Sweep s = aabb(pts, a); s.area < best.area)
          best = s, best_angle = a, better = true;
    }
  return best;
}

std::vector<Vec2> net_points(const Net& net) {
  std::vector<Vec2> pts;
  for (const auto& t : net.points) pts.insert(pts.end(), t.begin(), t.end());
  return pts;
}

TEST(Metrics, BoxOfARotatedRectangleIsTheRectangle) {
  std::vector<Vec2> pts = {{0, 0}, {4, 0}, {4, 1}, {0, 1}, {2, 0.5}, {1, 1}};
  for (Vec2& p : pts) p = rotate(p, 0.3) + Vec2{5, -2};
  const OrientedBox box = min_area_box(pts);
  EXPECT_NEAR(box.width(), 4, 1e-9);
  EXPECT_NEAR(box.height(), 1, 1e-9);
  for (Vec2 p : pts) {  // the rotation really puts every point into the box
    const Vec2 q = rotate(p, box.angle);
    EXPECT_GE(q.x, box.lo.x - 1e-9);
    EXPECT_LE(q.x, box.hi.x + 1e-9);
    EXPECT_GE(q.y, box.lo.y - 1e-9);
    EXPECT_LE(q.y, box.hi.y + 1e-9);
  }
}

TEST(Metrics, BoxMatchesARotationSweepOnRandomPointSets) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0, 1);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec2> pts(5 + trial * 7);
    for (Vec2& p : pts) p = {3 * g(rng), g(rng) * (1 + trial % 3)};
    const OrientedBox box = min_area_box(pts);
    const Sweep ref = brute_force(pts);
    // No rotation beats the box, and the sweep gets arbitrarily close to it.
    EXPECT_LE(box.area(), ref.area * (1 + 1e-12)) << "trial " << trial;
    EXPECT_GE(box.area(), ref.area * (1 - 1e-6)) << "trial " << trial;
    EXPECT_NEAR(aabb(pts, box.angle).area, box.area(), 1e-9 * box.area());
    EXPECT_GE(box.width(), box.height());
  }
}

TEST(Metrics, CoverageAndAspectRatioOfRealNetsMatchIndependentComputation) {
  auto meshes = test::test_data_meshes();
  meshes.emplace_back("cube", test::cube());
  meshes.emplace_back("tetrahedron", test::tetrahedron());
  ASSERT_GE(meshes.size(), 10u);
  for (const auto& [name, mesh] : meshes) {
    const Net net = test::bfs_net(mesh);
    const NetBoxMetrics m = net_metrics(mesh, net);
    const std::vector<Vec2> pts = net_points(net);
    const Sweep ref = brute_force(pts);
    double area2d = 0;  // face area from the 2D triangles: unfolding preserves it
    for (const auto& t : net.points) area2d += 0.5 * std::abs(cross(t[1] - t[0], t[2] - t[0]));
    EXPECT_NEAR(m.face_area, area2d, 1e-6 * area2d) << name;
    EXPECT_NEAR(m.coverage, area2d / ref.area, 1e-6 * m.coverage) << name;
    const double aspect = std::max(ref.w, ref.h) / std::min(ref.w, ref.h);
    EXPECT_NEAR(m.aspect_ratio, aspect, 1e-3 * aspect) << name;
    EXPECT_GT(m.coverage, 0) << name;
    EXPECT_LE(m.coverage, 1 + 1e-9) << name;
    EXPECT_EQ(m.faces, static_cast<int>(mesh.faces.size()));
  }
}

TEST(Folds, MountainAndValleyFollowTheDihedralSignOfAHandMadeRoof) {
  // Two triangles hinged on the x axis; the first lies in z = 0 facing +z.
  for (double z : {-1.0, 1.0}) {
    Mesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, z}};
    m.faces = {{0, 1, 2}, {1, 0, 3}};
    Net net;
    net.parent = {-1, 0};
    const double s = std::sqrt(2.0);  // the second triangle unfolds to (0.5, -sqrt(2))
    net.points = {{Vec2{0, 0}, Vec2{1, 0}, Vec2{0.5, 1}}, {Vec2{1, 0}, Vec2{0, 0}, Vec2{0.5, -s}}};
    const auto edges = classify_edges(m, net);
    int glued = 0;
    for (const NetEdge& e : edges) {
      if (e.kind == EdgeKind::Cut) continue;
      ++glued;
      // z < 0: the second face drops away below the first, a ridge seen from above: mountain.
      EXPECT_EQ(e.kind, z < 0 ? EdgeKind::Mountain : EdgeKind::Valley) << "z = " << z;
      EXPECT_NEAR(std::abs(e.fold), std::numbers::pi / 4, 1e-12);
    }
    EXPECT_EQ(glued, 1);
    EXPECT_EQ(
        std::count_if(edges.begin(), edges.end(), [](const NetEdge& e) { return e.b.face < 0; }),
        4);
  }
}

TEST(Folds, DentedOctahedronHasValleysExactlyAroundTheDent) {
  for (double top : {1.0, -0.4}) {
    const Mesh m = test::octahedron(top);
    const Net net = test::bfs_net(m);
    int cuts = 0, glued = 0;
    for (const NetEdge& e : classify_edges(m, net)) {
      const int u = m.faces[e.a.face][e.a.k], w = m.faces[e.a.face][(e.a.k + 1) % 3];
      const bool at_dent = top < 0 && (u == 4 || w == 4);
      if (e.kind == EdgeKind::Cut) {
        EXPECT_GE(e.cut_index, 0);
        ++cuts;
        continue;
      }
      ++glued;
      EXPECT_EQ(e.kind, at_dent ? EdgeKind::Valley : EdgeKind::Mountain) << u << "-" << w;
    }
    EXPECT_EQ(glued, 7);  // a tree on 8 faces
    EXPECT_EQ(cuts, 12 - 7);
  }
}

TEST(Folds, SidesThatMeetInTheNetWithoutATreeLinkAreGluedNotCut) {
  // A fan of six triangles around vertex 0 at height z over a flat hexagon. A BFS tree links
  // five of the six spokes; the sixth spoke's two sides meet in the net only when the fan is flat
  // (angle sum 360 degrees), and then the paper stays joined there: a fold without a tree link.
  for (double z : {0.0, 0.3}) {
    Mesh m;
    m.vertices.push_back({0, 0, z});
    for (int i = 0; i < 6; ++i) {
      const double t = i * std::numbers::pi / 3;
      m.vertices.push_back({std::cos(t), std::sin(t), 0});
    }
    for (int i = 0; i < 6; ++i) m.faces.push_back({0, i + 1, (i + 1) % 6 + 1});
    const Net net = test::bfs_net(m);
    int linked = 0, unlinked_glued = 0, cuts = 0, boundary = 0;
    for (const NetEdge& e : classify_edges(m, net)) {
      if (e.b.face < 0) {
        ++boundary;
        EXPECT_EQ(e.cut_index, -1);
        continue;
      }
      const bool link = net.parent[e.a.face] == e.b.face || net.parent[e.b.face] == e.a.face;
      linked += link;
      if (e.kind == EdgeKind::Cut) {
        EXPECT_FALSE(link);
        EXPECT_EQ(e.cut_index, cuts++);
        continue;
      }
      EXPECT_EQ(e.cut_index, -1);
      if (!link) ++unlinked_glued;
      if (z == 0) {
        EXPECT_EQ(e.kind, EdgeKind::Flat);
      }
    }
    EXPECT_EQ(boundary, 6);
    EXPECT_EQ(linked, 5);
    EXPECT_EQ(unlinked_glued, z == 0 ? 1 : 0) << "z = " << z;
    EXPECT_EQ(cuts, z == 0 ? 0 : 1) << "z = " << z;
  }
}

TEST(Folds, CoplanarDiagonalsOfACubeAreFlatAndCubeEdgesRightAngles) {
  const Mesh m = test::cube();
  const Net net = test::bfs_net(m);
  for (const NetEdge& e : classify_edges(m, net, {1.0})) {
    if (e.kind == EdgeKind::Cut) continue;
    const bool diagonal = e.a.face / 2 == e.b.face / 2;  // the two triangles of one quad
    EXPECT_EQ(e.kind, diagonal ? EdgeKind::Flat : EdgeKind::Mountain);
    EXPECT_NEAR(e.fold, diagonal ? 0 : std::numbers::pi / 2, 1e-12);
  }
}

}  // namespace
}  // namespace papernet
