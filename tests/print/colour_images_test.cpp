// The pixels a drawing of the whole net holds, foretold before drawing it (print/colour.h,
// colour_image_areas and colour_images_pixels: the engine lowers one drawing's resolution to
// what its time and kMostDrawingPixels allow), against the images colour_images then draws.
#include <gtest/gtest.h>

#include <cairo.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/unfold/net_check.h"
#include "core/unfold/tabu.h"
#include "print/colour.h"
#include "print/layout.h"
#include "tests/support/meshes.h"

namespace papernet {
namespace {

// The colour of `faces` faces: each one vertex colour, or none where `coloured` says so.
PrintColour flat_colour(std::size_t faces, const std::vector<bool>& coloured, double dpi) {
  PrintColour colour;
  colour.dpi = dpi;
  colour.faces.resize(faces);
  for (std::size_t f = 0; f < faces; ++f) {
    if (!coloured[f]) continue;
    ColourTriangle t;
    t.rgba = {{{0.8, 0.2, 0.1, 1}, {0.8, 0.2, 0.1, 1}, {0.8, 0.2, 0.1, 1}}};
    colour.faces[f].push_back(t);
  }
  return colour;
}

// The pixels of colour_images' images of the whole layout, unclipped.
double drawn_pixels(const PrintLayout& layout, const PrintColour& colour) {
  Box2 box = Box2::empty();
  for (const auto& face : layout.faces)
    for (Vec2 p : face) box.add(p);
  for (const Tab& tab : layout.tabs)
    for (Vec2 p : tab.corners) box.add(p);
  const double inf = std::numeric_limits<double>::infinity();
  double pixels = 0;
  for (const PageImage& image :
       colour_images(layout, colour, box.lo, box.hi, {0, 0}, {-inf, -inf}, {inf, inf}))
    pixels += double(cairo_image_surface_get_width(image.surface.get())) *
              cairo_image_surface_get_height(image.surface.get());
  return pixels;
}

// At a resolution under the image cap the foretold pixels are the drawn ones but for each
// image's bleed (two pixels past its box on every side) and whole pixels; above the cap each
// image holds kMaxImagePixels, foretold and drawn. Faces without colour are not drawn, and
// pieces of them alone hold no image.
TEST(ColourImages, ThePixelsForetoldAreThePixelsDrawn) {
  const Mesh mesh = test::octahedron();
  Progress quiet;
  const UnfoldResult unfolded = unfold_tabu(mesh, {}, quiet);
  ASSERT_TRUE(check_net(mesh, unfolded.net).ok());
  const PrintLayout layout = layout_net(mesh, unfolded.net, {});  // 200 mm across
  const std::size_t n = mesh.faces.size();
  for (const std::vector<bool>& coloured :
       {std::vector<bool>(n, true),
        std::vector<bool>{true, false, false, false, false, false, false, false}}) {
    ASSERT_EQ(coloured.size(), n);
    const std::vector<double> areas =
        colour_image_areas(layout, flat_colour(n, coloured, kDefaultColourDpi));
    ASSERT_EQ(areas.size(), 1u) << "one piece, coloured";
    for (const double dpi : {50.0, 150.0, 300.0}) {
      const PrintColour colour = flat_colour(n, coloured, dpi);
      const double foretold = colour_images_pixels(areas, dpi);
      const double drawn = drawn_pixels(layout, colour);
      ASSERT_LT(drawn, kMaxImagePixels) << "the cap is the next case";
      // The bleed (2 pixels past the box on each side) and whole pixels: each of the image's
      // sides at most 5 pixels longer than the box's, for a box not much longer than wide.
      const double side = std::sqrt(areas[0]) * dpi / 25.4;
      EXPECT_GE(drawn, foretold) << dpi << " dpi";
      EXPECT_LE(drawn, foretold + 4 * 5 * side + 100) << dpi << " dpi";
      std::printf("%g dpi: %.0f pixels foretold, %.0f drawn\n", dpi, foretold, drawn);
    }
    // Past the cap: the image's resolution is lowered to hold kMaxImagePixels.
    const double dpi = 25.4 * std::sqrt(4 * kMaxImagePixels / areas[0]);
    EXPECT_EQ(colour_images_pixels(areas, dpi), kMaxImagePixels);
    EXPECT_NEAR(drawn_pixels(layout, flat_colour(n, coloured, dpi)), kMaxImagePixels,
                0.01 * kMaxImagePixels);
  }
  const std::vector<double> none =
      colour_image_areas(layout, flat_colour(n, std::vector<bool>(n, false), 300));
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(colour_images_pixels(none, 300), 0);
}

}  // namespace
}  // namespace papernet
