#pragma once
// Printing the model's colour (docs/colour.md, "Printing"): each piece rasterised at the print's
// dpi from the affine map of each net triangle to its texture coordinates, glue tabs filled with
// the colour of the face they glue under, about a pixel of bleed past folds and cuts. One image
// per piece and page, drawn under the vector layers.

#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh/colour.h"
#include "core/vec.h"
#include "print/layout.h"

using cairo_surface_t = struct _cairo_surface;

namespace papernet {

/// Part of a printed face with one affine map to the texture: its corners in the face's
/// barycentric coordinates (a face coloured from its own corners has one, with the corners
/// (1,0,0), (0,1,0), (0,0,1)); a face coloured from a surface it approximates has many.
struct ColourTriangle {
  std::array<std::array<double, 3>, 3> at{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  std::array<UV, 3> uv{{{kNone, kNone}, {kNone, kNone}, {kNone, kNone}}};  ///< NaN: none
  /// Vertex colours (linear); NaN: none.
  std::array<RGBA, 3> rgba{
      {{kNone, kNone, kNone, kNone}, {kNone, kNone, kNone, kNone}, {kNone, kNone, kNone, kNone}}};
  int material = -1;
  /// The input face it is coloured from (a face's part of the surface it approximates), or -1.
  /// Parts of one printed face with the same source share one map and are filled together.
  long source = -1;
};

/// The default raster resolution of printed colour, dots per inch.
constexpr double kDefaultColourDpi = 300;
/// Limits of the `dpi` option.
constexpr double kMinColourDpi = 50, kMaxColourDpi = 1200;

/// A decoded texture ready to sample (cairo image surface), and how to sample it.
struct PrintTexture {
  std::shared_ptr<cairo_surface_t> surface;  ///< null when the image was not decoded
  int width = 0, height = 0;
  TextureSampler sampler;
};

/// What a print needs to colour a net: per face of the printed mesh its colour triangles (empty:
/// printed uncoloured), the materials and the decoded textures.
struct PrintColour {
  std::vector<std::vector<ColourTriangle>> faces;
  std::vector<Material> materials;
  std::vector<PrintTexture> textures;
  /// Per material: where its texture lets the paper show (alpha, A8; under Mask already
  /// thresholded with the factor's alpha), null when the material is opaque or its texture has
  /// no alpha.
  std::vector<std::shared_ptr<cairo_surface_t>> alpha;
  double dpi = kDefaultColourDpi;

  /// True when some face is coloured.
  bool any() const;
};

/// Something about the model's colour a person should know before printing (the result's
/// warnings): a code, how many textures or faces it concerns, and what it means for the print.
struct PrintNote {
  std::string code;
  std::size_t count = 1;
  std::string message;
};

/// The colour of a mesh of `faces` faces from its per-corner data (each face one
/// ColourTriangle). Textures are decoded here. Notes name what does not print as the model
/// says: a texture that does not decode (or exceeds the pixel limit) leaves its faces with the
/// material's factor only (`texture_not_printed`); textured faces without finite texture
/// coordinates print the factor too (`texture_coordinates_missing`), and clamped coordinates far
/// outside [0, 1] print the texture's edge (`texture_coordinates_out_of_range`).
PrintColour print_colour(const MeshColour& colour, std::size_t faces, double dpi,
                         std::vector<PrintNote>& notes);

/// The most pixels one image of colour_images holds (144 MB as ARGB): a piece larger than that
/// at the dpi asked (a whole A3 sheet at 300 dpi is 17 million) is drawn at a lower resolution,
/// so memory stays bounded.
constexpr double kMaxImagePixels = 36e6;

/// A piece's colour placed on a page: the image's top-left corner and size in page
/// millimetres (y down), its pixels an ARGB32 cairo image surface (transparent where nothing is
/// coloured).
struct PageImage {
  Vec2 at;
  double width = 0, height = 0;
  std::shared_ptr<cairo_surface_t> surface;
};

/// The colour images of every piece of `layout` (faces joined by folds) that is coloured and
/// meets the layout window [lo, hi] (y up), drawn as `map` puts the layout on the page: layout
/// point p to page point (at.x + p.x - lo.x, at.y + hi.y - p.y). Each image is cropped to the
/// page's [clip_lo, clip_hi].
std::vector<PageImage> colour_images(const PrintLayout& layout, const PrintColour& colour, Vec2 lo,
                                     Vec2 hi, Vec2 at, Vec2 clip_lo, Vec2 clip_hi);

/// The areas of colour_images' images of the whole of `layout`, unclipped, in square layout
/// units (millimetres for a printed layout): one for each coloured piece, the box of its faces
/// and tabs.
std::vector<double> colour_image_areas(const PrintLayout& layout, const PrintColour& colour);

/// The pixels images of `areas` (square millimetres) hold at `dpi`, each at most kMaxImagePixels.
double colour_images_pixels(const std::vector<double>& areas, double dpi);

/// The image's pixels as a PNG file's bytes.
std::string encode_png(cairo_surface_t* surface);

}  // namespace papernet
