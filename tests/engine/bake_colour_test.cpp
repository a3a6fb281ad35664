// The colour baked onto the faces of a coarser mesh (engine/colour.cpp, bake_colour): each face
// cut into small triangles coloured from the input surface nearest to them, as many as the
// print may draw.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/internal/colour.h"

namespace papernet::engine_detail {
namespace {

// A 100 x 100 flat square cut into a grid of 2 * 8 * 8 triangles (the input part), coloured
// linearly by position: red along x, green along y, blue 0.25. Its coarser mesh is the square
// as 2 triangles, so the colour of any point of a coarse face is that of the same position.
struct Square {
  Prepared input;
  std::vector<Piece> pieces;
};

RGBA colour_at(Vec3 p) { return {p.x / 100, p.y / 100, 0.25, 1}; }

Square square() {
  Square s;
  Mesh part;
  constexpr int kSide = 8;
  for (int j = 0; j <= kSide; ++j)
    for (int i = 0; i <= kSide; ++i)
      part.vertices.push_back({100.0 * i / kSide, 100.0 * j / kSide, 0});
  MeshColour colour;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      const int a = j * (kSide + 1) + i, b = a + 1, c = a + kSide + 1, d = c + 1;
      for (const std::array<int, 3> t : {std::array{a, b, d}, std::array{a, d, c}}) {
        part.faces.push_back(t);
        colour.colours.push_back({colour_at(part.vertices[t[0]]), colour_at(part.vertices[t[1]]),
                                  colour_at(part.vertices[t[2]])});
        colour.face_materials.push_back(-1);
      }
    }
  s.input.parts = {part};
  s.input.part_colours = {colour};
  Piece piece;
  piece.mesh.vertices = {{0, 0, 0}, {100, 0, 0}, {100, 100, 0}, {0, 100, 0}};
  piece.mesh.faces = {{0, 1, 2}, {0, 2, 3}};
  s.pieces = {piece};
  return s;
}

// Every small triangle's corners carry the input's colour at their position on the face.
void expect_input_colour(const Square& s, const BakedColour& baked) {
  const Mesh& mesh = s.pieces[0].mesh;
  for (std::size_t f = 0; f < baked.faces.size(); ++f)
    for (const ColourTriangle& t : baked.faces[f])
      for (int k = 0; k < 3; ++k) {
        const auto& w = t.at[k];
        const auto& face = mesh.faces[f];
        const Vec3 p = w[0] * mesh.vertices[face[0]] + w[1] * mesh.vertices[face[1]] +
                       w[2] * mesh.vertices[face[2]];
        const RGBA want = colour_at(p);
        for (int i = 0; i < 4; ++i) EXPECT_NEAR(t.rgba[k][i], want[i], 1e-9) << f << " " << k;
      }
}

std::size_t triangles(const BakedColour& baked) {
  std::size_t n = 0;
  for (const auto& face : baked.faces) n += face.size();
  return n;
}

// At 1 mm per unit, the faces' 141 mm diagonals are cut into the most steps a side (24): 576
// small triangles each, of side 2.5 mm or less, as usual.
TEST(BakeColour, CutsEachFaceIntoSmallTrianglesOfTheInputsColour) {
  const Square s = square();
  const BakedColour baked = bake_colour(s.pieces, s.input, 1.0, 1'000'000);
  ASSERT_EQ(baked.faces.size(), 2u);
  EXPECT_EQ(baked.faces[0].size(), 576u);
  EXPECT_EQ(baked.faces[1].size(), 576u);
  EXPECT_FALSE(baked.coarser);
  EXPECT_DOUBLE_EQ(baked.step_mm, kBakeStepMm);
  expect_input_colour(s, baked);
}

// Bounded to 100 small triangles, the side grows until there are at most that many (7 x 7 a
// face: 98), and they still carry the input's colour; bounded to 1, each face is one triangle.
TEST(BakeColour, AtMostTheTrianglesThePrintMayDraw) {
  const Square s = square();
  const BakedColour fewer = bake_colour(s.pieces, s.input, 1.0, 100);
  EXPECT_TRUE(fewer.coarser);
  EXPECT_LE(triangles(fewer), 100u);
  EXPECT_GE(triangles(fewer), 98u) << "the side is the smallest that keeps within the bound";
  EXPECT_GT(fewer.step_mm, kBakeStepMm);
  expect_input_colour(s, fewer);
  const BakedColour least = bake_colour(s.pieces, s.input, 1.0, 1);
  EXPECT_TRUE(least.coarser);
  EXPECT_EQ(triangles(least), 2u);
  expect_input_colour(s, least);
}

}  // namespace
}  // namespace papernet::engine_detail
