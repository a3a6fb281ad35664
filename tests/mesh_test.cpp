#include "core/mesh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/load.h"

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

TEST(Load, ObjQuadIsTriangulatedAndWelded) {
  // Two quads sharing an edge, written with duplicated vertices: welding must merge them.
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "v 1 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\n"
      "f 1 2 3 4\nf 5 6 7 8\n";
  const LoadedMesh loaded = load_mesh(obj, MeshFormat::Obj);
  EXPECT_EQ(loaded.mesh.faces.size(), 4u);
  EXPECT_EQ(loaded.mesh.vertices.size(), 6u);
  EXPECT_TRUE(loaded.triangulated);
}

}  // namespace
}  // namespace papernet
