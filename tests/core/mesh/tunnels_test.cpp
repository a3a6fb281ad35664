#include "core/mesh/tunnels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/io/load.h"
#include "core/mesh/validate.h"
#include "tests/support/meshes.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

double loop_length(const Mesh& mesh, const std::vector<int>& loop) {
  double length = 0;
  for (std::size_t i = 0; i < loop.size(); ++i)
    length += norm(mesh.vertices[loop[(i + 1) % loop.size()]] - mesh.vertices[loop[i]]);
  return length;
}

// A closed surface without tunnels has no loop that leaves it in one piece.
TEST(Tunnels, ASphereHasNone) {
  EXPECT_FALSE(shortest_tunnel_loop(test::cube(), 100));
  EXPECT_FALSE(shortest_tunnel_loop(test::octahedron(), 100));
  // Open: loops around the border separate too (and border loops are not taken).
  EXPECT_FALSE(shortest_tunnel_loop(
      test::height_field(6, [](double x, double y) { return 0.1 * x * y; }), 100));
}

// A torus of 16 x 8 quads, radii 2 and 0.7: the shortest loop goes once around its tube (8
// edges, a regular octagon of radius 0.7), not around its hole (16 edges of radius 1.3 at least).
TEST(Tunnels, TheShortestLoopOfATorusGoesAroundItsTube) {
  const Mesh torus = test::torus(16, 8);
  const double tube = 8 * 2 * 0.7 * std::sin(std::numbers::pi / 8);
  const auto loop = shortest_tunnel_loop(torus, 100);
  ASSERT_TRUE(loop);
  EXPECT_EQ(loop->size(), 8u);
  EXPECT_NEAR(loop_length(torus, *loop), tube, 1e-9);
  // No loop is that short when the bound is below it.
  EXPECT_FALSE(shortest_tunnel_loop(torus, 0.99 * tube));
}

// Plugging the torus where the loop runs leaves a sphere: manifold, oriented, closed, genus 0,
// with an octagon cap of 8 faces on each side of the cut.
TEST(Tunnels, APluggedTorusIsASphere) {
  const Mesh torus = test::torus(16, 8);
  const auto loop = shortest_tunnel_loop(torus, 100);
  ASSERT_TRUE(loop);
  const Mesh plugged = plug_tunnel(torus, *loop);
  EXPECT_EQ(plugged.faces.size(), torus.faces.size() + 16);
  EXPECT_EQ(plugged.vertices.size(), torus.vertices.size() + 8 + 2);
  const ValidationReport report = validate(plugged);
  EXPECT_TRUE(report.unfoldable()) << report.reason();
  EXPECT_EQ(report.genus, 0);
  EXPECT_EQ(report.boundary_edges, 0u);
  EXPECT_EQ(report.components, 1u);
  EXPECT_FALSE(shortest_tunnel_loop(plugged, 100));
}

// A CAD part with 24 small through-holes (trimesh ADIS16480, 600 faces): each plug takes one
// away, and the part stays a valid closed surface.
TEST(Tunnels, EachPlugOfACadPartTakesOneHandle) {
  Mesh part = load_mesh_file(test::test_data_dir() + "/trimesh_ADIS16480_600.obj").mesh;
  ASSERT_EQ(validate(part).genus, 24);
  const double diagonal = bounding_box_diagonal(part);
  double previous = 0;
  for (long genus = 23; genus >= 20; --genus) {
    const auto loop = shortest_tunnel_loop(part, diagonal);
    ASSERT_TRUE(loop);
    const double length = loop_length(part, *loop);
    EXPECT_GE(length, previous - 1e-9 * diagonal);  // shortest first
    previous = length;
    part = plug_tunnel(part, *loop);
    const ValidationReport report = validate(part);
    EXPECT_TRUE(report.unfoldable()) << report.reason();
    EXPECT_EQ(report.genus, genus);
    EXPECT_EQ(report.boundary_edges, 0u);
  }
}

}  // namespace
}  // namespace papernet
