#include "core/mesh/mesh.h"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace papernet
