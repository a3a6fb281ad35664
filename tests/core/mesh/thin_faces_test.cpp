#include "core/mesh/thin_faces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "core/io/load.h"
#include "core/mesh/hausdorff.h"
#include "core/mesh/validate.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

double lowest(const Mesh& mesh) {
  double h = 1e300;
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
    h = std::min(h, face_height(mesh, f));
  return h;
}

double area(const Mesh& mesh) {
  double a = 0;
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) a += face_area(mesh, f);
  return a;
}

// Two faces of a flat quadrilateral, one a sliver whose corner lies 0.01 from its long edge: the
// edge is flipped, both new faces are far thicker, and the quadrilateral is the same.
Mesh sliver_quad(double lift) {
  Mesh m;
  m.vertices = {{0, 0, 0}, {10, 0, 0}, {5, 0.01, lift}, {5, -5, 0}};
  m.faces = {{0, 1, 2}, {1, 0, 3}};
  return m;
}

TEST(ThinFaces, ASliverOfAFlatQuadrilateralIsFlipped) {
  Mesh m = sliver_quad(0);
  ASSERT_LT(lowest(m), 0.011);
  const double before = area(m);
  EXPECT_EQ(thicken_thin_faces(m, 1, 0.02), 1u);
  EXPECT_GT(lowest(m), 0.9);
  EXPECT_NEAR(area(m), before, 1e-9);
  const ValidationReport report = validate(m);
  EXPECT_TRUE(report.unfoldable()) << report.reason();
  // Thick enough already: nothing flips.
  EXPECT_EQ(thicken_thin_faces(m, 0.5, 0.02), 0u);
}

// Out of the plane by 1 (the flip would move the surface about that far): flipped only when that
// much move is allowed.
TEST(ThinFaces, AFlipThatMovesTheSurfaceTooFarIsNotMade) {
  Mesh m = sliver_quad(1);
  EXPECT_EQ(thicken_thin_faces(m, 2, 0.1), 0u);
  EXPECT_EQ(m.faces, sliver_quad(1).faces);
  EXPECT_EQ(thicken_thin_faces(m, 2, 2), 1u);
}

// A CAD part's slivers (trimesh ADIS16480, 600 faces, slivers along its edges): fewer faces under
// a hundredth of its diagonal high, the part still a valid closed surface within the move asked.
TEST(ThinFaces, ACadPartHasFewerSliversWithinTheMove) {
  const Mesh part = load_mesh_file(test::test_data_dir() + "/trimesh_ADIS16480_600.obj").mesh;
  const double diagonal = bounding_box_diagonal(part);
  const double thin = 0.01 * diagonal, move = 0.002 * diagonal;
  const auto count_thin = [&](const Mesh& m) {
    int n = 0;
    for (int f = 0; f < static_cast<int>(m.faces.size()); ++f) n += face_height(m, f) < thin;
    return n;
  };
  Mesh m = part;
  const std::size_t flips = thicken_thin_faces(m, thin, move);
  EXPECT_GT(flips, 0u);
  EXPECT_LT(count_thin(m), count_thin(part)) << flips << " flips";
  const ValidationReport report = validate(m);
  EXPECT_TRUE(report.unfoldable()) << report.reason();
  EXPECT_EQ(report.genus, 24);
  EXPECT_LE(hausdorff_distance(part, m).distance * diagonal, move * 1.01);
}

}  // namespace
}  // namespace papernet
