#include "core/mesh/mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/mesh/angle_defects.h"
#include "core/mesh/dual_graph.h"
#include "tests/support/meshes.h"

namespace papernet {
namespace {

TEST(Mesh, AreaNormalAndDiagonalOfAUnitRightTriangle) {
  Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.faces = {{0, 1, 2}};
  EXPECT_DOUBLE_EQ(face_area(m, 0), 0.5);
  EXPECT_DOUBLE_EQ(face_normal(m, 0).z, 1.0);
  EXPECT_DOUBLE_EQ(bounding_box_diagonal(m), std::sqrt(2.0));
}

// Angle defects sum to 2 pi times the Euler characteristic on a closed mesh (Gauss-Bonnet): 4 pi
// on the cube, whose every corner has a defect of pi / 2; 0 at a vertex inside a flat fan.
TEST(Mesh, AngleDefectsOfACubeAndOfAFlatFan) {
  const std::vector<double> cube = angle_defects(test::cube());
  ASSERT_EQ(cube.size(), 8u);
  double sum = 0;
  for (double d : cube) {
    EXPECT_NEAR(d, std::numbers::pi / 2, 1e-12);
    sum += d;
  }
  EXPECT_NEAR(sum, 4 * std::numbers::pi, 1e-12);
  Mesh fan;  // a square split into four triangles around its centre: the centre is flat
  fan.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  fan.faces = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  const std::vector<double> flat = angle_defects(fan);
  EXPECT_NEAR(flat[4], 0, 1e-12);
  EXPECT_EQ(flat[0], 0);  // on the boundary
}

TEST(Mesh, BoundingBoxHoldsEveryVertex) {
  const Box3 box = bounding_box(test::torus(8, 6));
  EXPECT_NEAR(box.lo.x, -2.7, 1e-12);
  EXPECT_NEAR(box.hi.z, 0.7 * std::sqrt(3.0) / 2, 1e-12);  // the ring at 60 and 120 degrees
  EXPECT_NEAR(box.size().x, 5.4, 1e-12);
  EXPECT_LT(bounding_box(Mesh{}).size().x, 0);  // nothing in it
}

// A dual graph is a tree when the faces are connected and their adjacency has no cycle: a closed
// surface never is, an open fan is, a fan closed into a ring is not, two faces apart are not.
TEST(Mesh, DualGraphIsATreeOnlyWithoutACycleOrASecondComponent) {
  EXPECT_FALSE(build_dual_graph(test::tetrahedron()).is_tree());
  EXPECT_FALSE(build_dual_graph(Mesh{}).is_tree());
  Mesh fan;  // three of the four triangles around a square's centre: a path of faces
  fan.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  fan.faces = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}};
  EXPECT_TRUE(build_dual_graph(fan).is_tree());
  fan.faces.push_back({3, 0, 4});  // the fourth closes the ring
  EXPECT_FALSE(build_dual_graph(fan).is_tree());
  Mesh one;
  one.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}, {6, 0, 0}, {5, 1, 0}};
  one.faces = {{0, 1, 2}};
  EXPECT_TRUE(build_dual_graph(one).is_tree());
  one.faces.push_back({3, 4, 5});  // one face each of two parts: no edge, two components
  EXPECT_FALSE(build_dual_graph(one).is_tree());
}

}  // namespace
}  // namespace papernet
