// The views of the model on the overview page (print/model_view.h): on a cube whose six sides
// are six pieces, seen from a corner, exactly the three sides facing the viewer are numbered,
// each where the geometry puts it; the image covers the box asked at its resolution.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <vector>

#include "core/io/image.h"
#include "print/model_view.h"

namespace papernet::test {
namespace {

/// The unit cube [-1, 1]^3, faces counter-clockwise from outside; the pieces by side: 0 +x,
/// 1 -x, 2 +y, 3 -y, 4 +z, 5 -z.
struct Cube {
  Mesh mesh;
  std::vector<int> piece;
};

Cube cube() {
  Cube c;
  for (int i = 0; i < 8; ++i)
    c.mesh.vertices.push_back({i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0});
  // Each side: its four corners counter-clockwise seen from outside, as two triangles.
  const std::array<std::array<int, 4>, 6> sides{
      {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}}};
  for (int s = 0; s < 6; ++s) {
    const auto& q = sides[s];
    c.mesh.faces.push_back({q[0], q[1], q[2]});
    c.mesh.faces.push_back({q[0], q[2], q[3]});
    c.piece.insert(c.piece.end(), 2, s);
  }
  return c;
}

std::map<int, Vec2> numbers(const ModelView& view) {
  std::map<int, Vec2> out;
  for (const ModelView::Number& n : view.numbers) {
    EXPECT_FALSE(out.contains(n.piece)) << "P" << n.piece + 1 << " numbered twice";
    out[n.piece] = n.at;
  }
  return out;
}

TEST(ModelView, TheCubeSeenFromACornerShowsItsThreeNearSidesNumbered) {
  const Cube c = cube();
  for (const double s : {1.0, -1.0}) {
    const ModelView view =
        draw_model_view(c.mesh, c.piece, {s, s, s}, {0, 0, 1}, {10, 20}, {90, 100}, 100);
    // Z up; x on the page is up x toward: (-1, 1, 0) from (1, 1, 1), so the +y side is to the
    // right of the +x side and the top above both; (1, -1, 0) from (-1, -1, -1), so the -y side
    // is to the right of the -x side and the bottom below both (seen from beneath, z still up).
    const std::map<int, Vec2> n = numbers(view);
    ASSERT_EQ(n.size(), 3u) << "from " << s;
    const int x = s > 0 ? 0 : 1, y = s > 0 ? 2 : 3, z = s > 0 ? 4 : 5;
    ASSERT_TRUE(n.contains(x) && n.contains(y) && n.contains(z)) << "from " << s;
    EXPECT_LT(n.at(x).x, n.at(y).x) << "from " << s;
    if (s > 0)
      EXPECT_LT(n.at(z).y, std::min(n.at(x).y, n.at(y).y));
    else
      EXPECT_GT(n.at(z).y, std::max(n.at(x).y, n.at(y).y));
    // The cube fits the square box, centred: its outline is a hexagon about (50, 60), and
    // each side's number lies in the middle third of the box.
    for (const auto& [p, at] : n) {
      EXPECT_NEAR(at.x, 50, 30) << "P" << p + 1;
      EXPECT_NEAR(at.y, 60, 30) << "P" << p + 1;
    }
    for (const ModelView::Number& k : view.numbers) EXPECT_EQ(k.size, kViewNumberMm[0]);
  }
  const ModelView view =
      draw_model_view(c.mesh, c.piece, {1, 1, 1}, {0, 0, 1}, {10, 20}, {90, 100}, 100);
  ASSERT_TRUE(view.image.surface);
  EXPECT_EQ(view.image.at.x, 10);
  EXPECT_EQ(view.image.at.y, 20);
  EXPECT_EQ(view.image.width, 80);
  const Image image = decode_image(encode_png(view.image.surface.get()));
  EXPECT_EQ(image.width, 315);  // 80 mm at 100 dpi
  EXPECT_EQ(image.height, 315);
}

// Seen nearly along the x axis (and level: the top and bottom edge-on), in a box twice as wide
// as the cube, the +x side holds its number; the +y side shows as a sliver too thin for one
// (about 1.7 mm), so its number stands beside the cube with a line to the sliver; the hidden and
// edge-on sides get none.
TEST(ModelView, ASideThatShowsTooLittleIsNumberedBesideTheModel) {
  const Cube c = cube();
  const ModelView view =
      draw_model_view(c.mesh, c.piece, {1, 0.03, 0}, {0, 0, 1}, {0, 0}, {120, 60}, 100);
  std::map<int, ModelView::Number> n;
  for (const ModelView::Number& k : view.numbers) n[k.piece] = k;
  ASSERT_EQ(n.size(), 2u);
  ASSERT_TRUE(n.contains(0) && n.contains(2));
  // The cube fills the box's height and the middle half of its width: x from about 31 to 89.
  EXPECT_NEAR(n[0].at.x, 60, 10);
  EXPECT_TRUE(n[0].from == n[0].at && n[0].to == n[0].at) << "on its side, no line";
  EXPECT_GT(n[2].at.x, 89) << "P3 beside the cube, at its right";
  EXPECT_FALSE(n[2].from == n[2].to) << "P3 has a line to its side";
  EXPECT_GT(n[2].to.x, 86) << "the +y side's sliver is at the cube's right";
  EXPECT_LT(n[2].to.x, 90);
}

// Without pieces for its faces, or without room, there is nothing to draw.
TEST(ModelView, NothingToDrawDrawsNothing) {
  const Cube c = cube();
  EXPECT_FALSE(
      draw_model_view(c.mesh, {}, {1, 1, 1}, {0, 0, 1}, {0, 0}, {60, 60}, 100).image.surface);
  EXPECT_FALSE(
      draw_model_view(c.mesh, c.piece, {1, 1, 1}, {0, 0, 1}, {0, 0}, {0, 60}, 100).image.surface);
}

}  // namespace
}  // namespace papernet::test
