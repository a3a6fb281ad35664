#include "core/mesh/thin_plates.h"

#include <gtest/gtest.h>

#include <optional>

#include "core/mesh/hausdorff.h"
#include "core/mesh/validate.h"
#include "tests/support/meshes.h"

namespace papernet {
namespace {

double area(const Mesh& mesh) {
  double a = 0;
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) a += face_area(mesh, f);
  return a;
}

// The unit cube stretched to a box of sides x, y and z.
Mesh box(double x, double y, double z) {
  Mesh m = test::cube();
  for (Vec3& v : m.vertices) v = {v.x * x, v.y * y, v.z * z};
  return m;
}

// A square of side 10 with a pyramid of height `h` on it: the four sides hold more area than the
// base, and their apex is not flat.
Mesh low_pyramid(double h) {
  Mesh m;
  m.vertices = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}, {5, 5, h}};
  m.faces = {{0, 2, 1}, {0, 3, 2}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  return m;
}

// A plate of 40 x 20 x 1 is taken as one of its large sides: two faces, an open square of
// 800, one boundary loop, as far from the plate as it is thick.
TEST(ThinPlates, AThinBoxIsOneOfItsLargeSides) {
  const Mesh plate = box(40, 20, 1);
  const std::optional<Mesh> side = plate_side(plate);
  ASSERT_TRUE(side);
  EXPECT_EQ(side->faces.size(), 2u);
  EXPECT_NEAR(area(*side), 800, 1e-9);
  const ValidationReport report = validate(*side);
  EXPECT_TRUE(report.unfoldable()) << report.reason();
  EXPECT_EQ(report.boundary_loops, 1u);
  const double diagonal = bounding_box_diagonal(plate);
  EXPECT_NEAR(approximation_distance(plate, *side) * diagonal, 1, 1e-6);
}

// Of two sides that each hold a third of the area, the flat one: the base of a low pyramid
// prints as one square, its four sides only with a cut to the apex.
TEST(ThinPlates, TheFlatSideIsTakenOverALargerCurvedOne) {
  const Mesh pyramid = low_pyramid(0.5);
  const std::optional<Mesh> side = plate_side(pyramid);
  ASSERT_TRUE(side);
  EXPECT_EQ(side->faces.size(), 2u);
  EXPECT_NEAR(area(*side), 100, 1e-9);
  EXPECT_EQ(side->vertices.size(), 4u);
  for (const Vec3& v : side->vertices) EXPECT_EQ(v.z, 0);
}

// No side holds a third of the area: a cube's six sides a sixth each, and a box of 1 x 1 x 40
// (a rod) four sides of nearly a quarter. A smooth surface is one sheet: the torus, whose
// neighbouring faces meet at small angles, has no side to take.
TEST(ThinPlates, CubesRodsAndSmoothSurfacesHaveNoSide) {
  EXPECT_FALSE(plate_side(test::cube()));
  EXPECT_FALSE(plate_side(box(1, 1, 40)));
  EXPECT_FALSE(plate_side(test::torus(24, 12)));
}

// A box whose large sides hold under a third of its area each (40 x 20 x 20: 800 of 4,000) is no
// plate; 40 x 20 x 5 (800 of 2,200) is one, as far from its side as it is thick (the caller decides
// whether that is thin).
TEST(ThinPlates, ABoxIsAPlateOnlyWhenItsLargeSidesHoldAThird) {
  EXPECT_FALSE(plate_side(box(40, 20, 20)));
  const Mesh thick = box(40, 20, 5);
  const std::optional<Mesh> side = plate_side(thick);
  ASSERT_TRUE(side);
  EXPECT_NEAR(approximation_distance(thick, *side) * bounding_box_diagonal(thick), 5, 1e-6);
}

// An open square with a flap folded up at its rim: the square is nearly all of the area, no side
// of a plate (taking it would cut the flap off).
TEST(ThinPlates, AnOpenSurfaceWithAFoldedFlapHasNoSide) {
  Mesh sheet = test::height_field(4, [](double, double) { return 0.0; });
  // Vertices i * 5 + j at x = -1 + i / 2, y = -1 + j / 2: the rim edge from (-1, -1) to
  // (-0.5, -1) runs 0 -> 5 in the face {0, 5, 6}; the flap runs it the other way.
  sheet.vertices.push_back({-0.75, -1, 0.4});
  sheet.faces.push_back({5, 0, static_cast<int>(sheet.vertices.size()) - 1});
  ASSERT_TRUE(validate(sheet).unfoldable()) << validate(sheet).reason();
  EXPECT_FALSE(plate_side(sheet));
}

}  // namespace
}  // namespace papernet
