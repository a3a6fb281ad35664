#pragma once
// Private to print/: the model's colour drawn into a piece's image (print/colour.cpp), one colour
// triangle at a time (print/colour_paint.cpp), its texture sampled through the triangle's map to
// its texels (print/colour_texture.cpp). cairo does the sampling and the filling.

#include <cairo.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <vector>

#include "core/mesh/colour.h"
#include "core/vec.h"
#include "print/colour.h"

namespace papernet::print_detail {

using SurfacePtr = std::shared_ptr<cairo_surface_t>;

/// `s`, destroyed with its last owner.
inline SurfacePtr own(cairo_surface_t* s) { return SurfacePtr(s, cairo_surface_destroy); }

inline bool finite(const UV& uv) { return std::isfinite(uv[0]) && std::isfinite(uv[1]); }
inline bool finite(const RGBA& c) {
  return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]);
}

/// The texture `t` prints from: its material's, decoded, where its texture coordinates are
/// finite; null otherwise.
const PrintTexture* texture_of(const ColourTriangle& t, const PrintColour& colour);

/// Traces the closed polygon through the points `p` (a path for cairo to fill).
template <typename Points>
void trace(cairo_t* cr, const Points& p) {
  cairo_move_to(cr, p[0].x, p[0].y);
  for (std::size_t i = 1; i < p.size(); ++i) cairo_line_to(cr, p[i].x, p[i].y);
  cairo_close_path(cr);
}

// Polygons filled together (nonzero winding: each triangle turned the same way round, so their
// union is filled where they overlap).
using Outline = std::vector<std::vector<Vec2>>;

inline void trace(cairo_t* cr, const Outline& outline) {
  for (const auto& polygon : outline) trace(cr, polygon);
}

// The texture through a triangle's map (print/colour_texture.cpp).

// Under clamp sampling, a polygon whose texture coordinates stay within this far of [0, 1] is
// drawn with one pattern (the pattern's pad extend is the clamp).
constexpr double kNearUv = 2;

// Part of a polygon filled from the texture through one matrix (page millimetres to texels).
struct TexturePart {
  Outline outline;
  cairo_matrix_t matrix;
};

/// The texture over `outline`, coloured as the triangle with page corners p and texture
/// coordinates uv maps it (extended past the triangle's sides): the parts to fill, each with its
/// matrix. Empty when the triangle's map is degenerate or repeats too often; the caller then
/// prints the texel at its centre.
std::vector<TexturePart> texture_parts(const PrintTexture& tex, const std::array<Vec2, 3>& p,
                                       std::array<UV, 3> uv, const Outline& outline);

/// `surface` (a texture, or its alpha) through `matrix`, sampled as `sampler` says (the caller
/// destroys the pattern).
cairo_pattern_t* sampled(cairo_surface_t* surface, const TextureSampler& sampler,
                         const cairo_matrix_t& matrix);

/// The texture through `matrix` as the source.
void set_texture_source(cairo_t* cr, const PrintTexture& tex, const cairo_matrix_t& matrix);

/// Fills each part from the texture.
void fill_texture(cairo_t* cr, const PrintTexture& tex, const std::vector<TexturePart>& parts);

/// The texture at the centroid of uv, for a triangle whose map to the texture is degenerate
/// (a point or a line): sampled as the pattern would, bilinearly between the four texels around
/// it (nearest under a nearest filter), each wrapped by the sampler.
std::array<double, 3> texel_at(const PrintTexture& tex, const std::array<UV, 3>& uv);

// One colour triangle painted (print/colour_paint.cpp).

/// Fills the triangles at page corners ps with the colour of t placed at ps[0] (those after it
/// share its map: placed parts of one face coloured from one source face), and `bleed`
/// millimetres around them; with `area`, that polygon instead, coloured by the triangle's map
/// extended past its sides.
void paint(cairo_t* cr, const ColourTriangle& t, const std::vector<std::array<Vec2, 3>>& ps,
           const PrintColour& colour, double bleed, const std::vector<Vec2>* area = nullptr);

}  // namespace papernet::print_detail
