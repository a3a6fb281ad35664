// Colour rasterised per piece (docs/colour.md, "Printing"). cairo does the sampling: each
// triangle is filled from the texture through the affine map of its page corners to its texels
// (CAIRO_FILTER_GOOD filters a minified texture over the texels a pixel covers), vertex colours
// are a mesh gradient, and colour factors multiply (CAIRO_OPERATOR_MULTIPLY).
#include "print/colour.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/errors.h"
#include "core/io/image.h"
#include "core/unfold/overlap.h"
#include "core/union_find.h"

namespace papernet {
namespace {

using SurfacePtr = std::shared_ptr<cairo_surface_t>;

SurfacePtr own(cairo_surface_t* s) { return SurfacePtr(s, cairo_surface_destroy); }

bool finite(const UV& uv) { return std::isfinite(uv[0]) && std::isfinite(uv[1]); }
bool finite(const RGBA& c) {
  return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]);
}

// glTF's factors and vertex colours are linear; textures and paper are sRGB.
double srgb(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

SurfacePtr texture_surface(const Image& image) {
  SurfacePtr s = own(cairo_image_surface_create(CAIRO_FORMAT_RGB24, image.width, image.height));
  if (cairo_surface_status(s.get()) != CAIRO_STATUS_SUCCESS) return nullptr;
  cairo_surface_flush(s.get());
  unsigned char* data = cairo_image_surface_get_data(s.get());
  const int stride = cairo_image_surface_get_stride(s.get());
  for (int y = 0; y < image.height; ++y) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
    const std::uint8_t* in = image.rgba.data() + static_cast<std::size_t>(y) * image.width * 4;
    for (int x = 0; x < image.width; ++x, in += 4)  // alpha apart (alpha_surface)
      row[x] = 0xff000000u | (std::uint32_t{in[0]} << 16) | (std::uint32_t{in[1]} << 8) | in[2];
  }
  cairo_surface_mark_dirty(s.get());
  return s;
}

// The image's alpha as an A8 surface: as it is, or 255 where alpha times `factor` reaches
// `cutoff` (0 elsewhere) when `cutoff` >= 0. Null when every pixel is opaque.
SurfacePtr alpha_surface(const Image& image, double factor, double cutoff) {
  bool any = false;
  for (std::size_t i = 3; i < image.rgba.size() && !any; i += 4) any = image.rgba[i] < 255;
  if (!any) return nullptr;
  SurfacePtr s = own(cairo_image_surface_create(CAIRO_FORMAT_A8, image.width, image.height));
  if (cairo_surface_status(s.get()) != CAIRO_STATUS_SUCCESS) return nullptr;
  cairo_surface_flush(s.get());
  unsigned char* data = cairo_image_surface_get_data(s.get());
  const int stride = cairo_image_surface_get_stride(s.get());
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t a = image.rgba[(static_cast<std::size_t>(y) * image.width + x) * 4 + 3];
      data[static_cast<std::ptrdiff_t>(y) * stride + x] =
          cutoff < 0 ? a : (a / 255.0 * factor >= cutoff ? 255 : 0);
    }
  cairo_surface_mark_dirty(s.get());
  return s;
}

cairo_extend_t extend_of(int wrap) {
  switch (wrap) {
    case 33071:
      return CAIRO_EXTEND_PAD;
    case 33648:
      return CAIRO_EXTEND_REFLECT;
    default:
      return CAIRO_EXTEND_REPEAT;
  }
}

const PrintTexture* texture_of(const ColourTriangle& t, const PrintColour& colour);

// How much of the triangle's material covers the paper by its factor's alpha (docs/colour.md,
// "Alpha"): 1 when opaque; under Blend the alpha; under Mask 1 or 0 by the cutoff.
double factor_cover(const ColourTriangle& t, const PrintColour& colour) {
  if (t.material < 0 || t.material >= static_cast<int>(colour.materials.size())) return 1;
  const Material& m = colour.materials[t.material];
  const double a = std::clamp(m.base_color[3], 0.0, 1.0);
  switch (m.alpha_mode) {
    case AlphaMode::Blend:
      return a;
    case AlphaMode::Mask:
      return a >= m.alpha_cutoff ? 1 : 0;
    case AlphaMode::Opaque:
      break;
  }
  return 1;
}

// The triangle's own colour factor (material × vertex colours), linear, at barycentric point w:
// vertex colours are interpolated as glTF has them.
std::array<double, 3> linear_factor_at(const ColourTriangle& t, const PrintColour& colour,
                                       const std::array<double, 3>& w) {
  RGBA c{1, 1, 1, 1};
  if (t.material >= 0 && t.material < static_cast<int>(colour.materials.size()))
    c = colour.materials[t.material].base_color;
  if (finite(t.rgba[0]) && finite(t.rgba[1]) && finite(t.rgba[2]))
    for (int i = 0; i < 3; ++i)
      c[i] *= w[0] * t.rgba[0][i] + w[1] * t.rgba[1][i] + w[2] * t.rgba[2][i];
  return {c[0], c[1], c[2]};
}

// The same turned into sRGB. Without a texture, the paper shows through as the factor's alpha
// says.
std::array<double, 3> factor_at(const ColourTriangle& t, const PrintColour& colour,
                                const std::array<double, 3>& w) {
  const std::array<double, 3> c = linear_factor_at(t, colour, w);
  std::array<double, 3> out{srgb(c[0]), srgb(c[1]), srgb(c[2])};
  if (!texture_of(t, colour)) {
    const double cover = factor_cover(t, colour);
    for (double& x : out) x = x * cover + (1 - cover);
  }
  return out;
}

std::array<double, 3> corner_colour(const ColourTriangle& t, const PrintColour& colour, int k) {
  std::array<double, 3> w{0, 0, 0};
  w[k] = 1;
  return factor_at(t, colour, w);
}

// A gradient's triangle is cut into at most this many steps a side: cairo interpolates a mesh
// patch's corner colours in sRGB, so the linear interpolation is followed patch by patch (from
// black to white, 0.235 off at the middle in one patch, under 0.015 in 4 x 4).
constexpr int kGradientSteps = 4;

// The widest sRGB range of a channel across one patch: interpolated in sRGB instead of linear, a
// range of 8/255 is at most 0.4/255 off, under half a step of 8-bit colour. A triangle whose
// corners differ by less is one patch: the small triangles that colour a coarser face
// (engine/colour.cpp) differ by a step or two: the Menger sponge's 1.5 million of them drew in
// 36 s instead of 53 (at 300 dpi, before write_gradient below).
constexpr double kPatchRange = 8.0 / 255;

// Steps a side for a gradient between corner colours c: each patch spans at most kPatchRange.
int gradient_steps(const std::array<std::array<double, 3>, 3>& c) {
  double range = 0;
  for (int i = 0; i < 3; ++i)
    range = std::max({range, std::abs(c[0][i] - c[1][i]), std::abs(c[1][i] - c[2][i]),
                      std::abs(c[2][i] - c[0][i])});
  return std::clamp(static_cast<int>(std::ceil(range / kPatchRange)), 1, kGradientSteps);
}

const PrintTexture* texture_of(const ColourTriangle& t, const PrintColour& colour) {
  if (t.material < 0 || t.material >= static_cast<int>(colour.materials.size())) return nullptr;
  const int k = colour.materials[t.material].texture;
  if (k < 0 || k >= static_cast<int>(colour.textures.size())) return nullptr;
  const PrintTexture& tex = colour.textures[k];
  if (!tex.surface || !finite(t.uv[0]) || !finite(t.uv[1]) || !finite(t.uv[2])) return nullptr;
  return &tex;
}

bool coloured(const ColourTriangle& t, const PrintColour& colour) {
  return texture_of(t, colour) ||
         (t.material >= 0 && t.material < static_cast<int>(colour.materials.size())) ||
         (finite(t.rgba[0]) && finite(t.rgba[1]) && finite(t.rgba[2]));
}

template <typename Points>
void trace(cairo_t* cr, const Points& p) {
  cairo_move_to(cr, p[0].x, p[0].y);
  for (std::size_t i = 1; i < p.size(); ++i) cairo_line_to(cr, p[i].x, p[i].y);
  cairo_close_path(cr);
}

// Polygons filled together (nonzero winding: each triangle turned the same way round, so their
// union is filled where they overlap).
using Outline = std::vector<std::vector<Vec2>>;

void trace(cairo_t* cr, const Outline& outline) {
  for (const auto& polygon : outline) trace(cr, polygon);
}

// An affine function of page position: a · p + c.
struct Affine {
  Vec2 a;
  double c = 0;
  double operator()(Vec2 p) const { return dot(a, p) + c; }
};

// Texture coordinates far out of [0, 1] are brought near before cairo sees them: pixman holds
// texel coordinates in 16.16 fixed point (at most 32767). Repeat and mirror move a triangle by
// whole periods (even ones for mirror); clamp splits it where u and v leave [0, 1] (below).
// A triangle spread over more periods than this (a texture repeated hundreds of times across
// one face) prints the texel at its centre.
constexpr double kMaxPeriods = 64;
// Under clamp sampling, a polygon whose texture coordinates stay within this far of [0, 1] is
// drawn with one pattern (the pattern's pad extend is the clamp).
constexpr double kNearUv = 2;

// Part of a polygon filled from the texture through one matrix (page millimetres to texels).
struct TexturePart {
  Outline outline;
  cairo_matrix_t matrix;
};

// The part of polygon `poly` where f(p) >= level (above) or f(p) <= level (!above).
std::vector<Vec2> clip(const std::vector<Vec2>& poly, const Affine& f, double level, bool above) {
  std::vector<Vec2> out;
  auto inside = [&](double x) { return above ? x >= level : x <= level; };
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    const double fa = f(a), fb = f(b);
    if (inside(fa)) out.push_back(a);
    if (inside(fa) != inside(fb)) out.push_back(a + ((level - fa) / (fb - fa)) * (b - a));
  }
  return out;
}

cairo_matrix_t matrix_of(const Affine& x, const Affine& y) {
  cairo_matrix_t m;
  cairo_matrix_init(&m, x.a.x, y.a.x, x.a.y, y.a.y, x.c, y.c);
  return m;
}

// The texture over `outline`, coloured as the triangle with page corners p and texture
// coordinates uv maps it (extended past the triangle's sides): the parts to fill, each with its
// matrix. Empty when the triangle's map is degenerate or repeats too often; the caller then
// prints the texel at its centre.
std::vector<TexturePart> texture_parts(const PrintTexture& tex, const std::array<Vec2, 3>& p,
                                       std::array<UV, 3> uv, const Outline& outline) {
  const bool clamp = tex.sampler.wrap_s == 33071;
  if (!clamp)
    for (int axis = 0; axis < 2; ++axis) {
      const double mean = uv[0][axis] / 3 + uv[1][axis] / 3 + uv[2][axis] / 3;
      const int wrap = axis == 0 ? tex.sampler.wrap_s : tex.sampler.wrap_t;
      const double period = wrap == 33648 ? 2 : 1;
      const double shift = period * std::floor(mean / period);
      for (UV& c : uv) c[axis] -= shift;
    }
  // Texture coordinates on a line (a face mapped onto a strip of texels): the corner off the
  // longest side moved a thousandth of a texel across it, so that cairo samples along the line.
  {
    std::array<Vec2, 3> t;
    for (int k = 0; k < 3; ++k) t[k] = {uv[k][0] * tex.width, uv[k][1] * tex.height};
    int side = 0;
    for (int k = 1; k < 3; ++k)
      if (norm(t[(k + 1) % 3] - t[k]) > norm(t[(side + 1) % 3] - t[side])) side = k;
    const Vec2 along = t[(side + 1) % 3] - t[side];
    const double length = norm(along);
    if (length > 1e-6 && std::abs(cross(t[1] - t[0], t[2] - t[0])) < 1e-6 * length * length) {
      const Vec2 across = (1e-3 / length) * Vec2{-along.y, along.x};
      UV& off = uv[(side + 2) % 3];
      off[0] += across.x / tex.width;
      off[1] += across.y / tex.height;
    }
  }
  // u and v of a page point: [u1-u0 u2-u0] · [e1 e2]⁻¹ · (p - p0) + u0.
  const Vec2 e1 = p[1] - p[0], e2 = p[2] - p[0];
  const double det = cross(e1, e2);
  const double area =
      (uv[1][0] - uv[0][0]) * (uv[2][1] - uv[0][1]) - (uv[2][0] - uv[0][0]) * (uv[1][1] - uv[0][1]);
  const double texels = area * tex.width * tex.height;
  if (!(std::abs(det) > 1e-12) || !(std::abs(texels) > 1e-9) || !std::isfinite(texels)) return {};
  const Vec2 r1{e2.y / det, -e2.x / det}, r2{-e1.y / det, e1.x / det};  // rows of [e1 e2]⁻¹
  std::array<Affine, 2> map;
  std::array<double, 2> lo{}, hi{};
  for (int axis = 0; axis < 2; ++axis) {
    const double d1 = uv[1][axis] - uv[0][axis], d2 = uv[2][axis] - uv[0][axis];
    map[axis].a = d1 * r1 + d2 * r2;
    map[axis].c = uv[0][axis] - dot(map[axis].a, p[0]);
    lo[axis] = std::numeric_limits<double>::infinity();
    hi[axis] = -lo[axis];
    for (const auto& polygon : outline)
      for (Vec2 q : polygon) {
        lo[axis] = std::min(lo[axis], map[axis](q));
        hi[axis] = std::max(hi[axis], map[axis](q));
      }
  }
  const std::array<double, 2> n{static_cast<double>(tex.width), static_cast<double>(tex.height)};
  auto texel_map = [&](int axis) { return Affine{n[axis] * map[axis].a, n[axis] * map[axis].c}; };
  // pixman's limit, with room for the bleed and filtering.
  const bool fixed_point = std::max(std::abs(lo[0]), std::abs(hi[0])) * n[0] <= 16384 &&
                           std::max(std::abs(lo[1]), std::abs(hi[1])) * n[1] <= 16384;
  const bool near =
      fixed_point && (clamp ? lo[0] >= -kNearUv && lo[1] >= -kNearUv && hi[0] <= 1 + kNearUv &&
                                  hi[1] <= 1 + kNearUv
                            : hi[0] - lo[0] <= kMaxPeriods && hi[1] - lo[1] <= kMaxPeriods);
  if (near) return {{outline, matrix_of(texel_map(0), texel_map(1))}};
  if (!clamp) return {};
  // Clamp far out: where u < 0 every point shows the first texel column, where u > 1 the last
  // (and so for v). Each of the nine parts the lines u, v = 0, 1 cut the outline into gets a
  // matrix that keeps its texels near: the axis in [0, 1] as the triangle maps it, an axis past
  // an edge held just beyond that edge (a quarter texel of spread over the part, along the
  // other axis's gradient's normal, keeps the matrix invertible). The middle part is drawn
  // last, over the antialiased seams.
  std::vector<TexturePart> parts;
  auto add = [&](std::array<int, 2> side) {  // per axis 0: below 0, 1: in [0, 1], 2: above 1
    Outline polys;
    Box2 box = Box2::empty();
    for (std::vector<Vec2> poly : outline) {
      for (int axis = 0; axis < 2 && poly.size() >= 3; ++axis) {
        if (side[axis] != 2) poly = clip(poly, map[axis], side[axis] == 0 ? 0 : 1, false);
        if (side[axis] != 0 && poly.size() >= 3)
          poly = clip(poly, map[axis], side[axis] == 2 ? 1 : 0, true);
      }
      if (poly.size() < 3) continue;
      for (Vec2 q : poly) box.add(q);
      polys.push_back(std::move(poly));
    }
    if (polys.empty()) return;
    const Vec2 centre = 0.5 * (box.lo + box.hi);
    const double spread = 0.25 / std::max(norm(box.size()), 1e-9);
    std::array<Affine, 2> row;
    for (int axis = 0; axis < 2; ++axis) {
      if (side[axis] == 1) {
        row[axis] = texel_map(axis);
        continue;
      }
      const int other = 1 - axis;
      Vec2 q = axis == 0 ? Vec2{1, 0} : Vec2{0, 1};
      if (side[other] == 1) {
        const Vec2 g = map[other].a;
        q = (1 / norm(g)) * Vec2{-g.y, g.x};
      }
      const double held = side[axis] == 0 ? -0.75 : n[axis] + 0.75;
      row[axis] = {spread * q, held - spread * dot(q, centre)};
    }
    parts.push_back({std::move(polys), matrix_of(row[0], row[1])});
  };
  for (int su = 0; su < 3; ++su)
    for (int sv = 0; sv < 3; ++sv)
      if (su != 1 || sv != 1) add({su, sv});
  add({1, 1});
  return parts;
}

// `surface` (a texture, or its alpha) through `matrix`, sampled as `sampler` says.
cairo_pattern_t* sampled(cairo_surface_t* surface, const TextureSampler& sampler,
                         const cairo_matrix_t& matrix) {
  cairo_pattern_t* pattern = cairo_pattern_create_for_surface(surface);
  cairo_pattern_set_matrix(pattern, &matrix);
  cairo_pattern_set_extend(pattern, extend_of(sampler.wrap_s));
  cairo_pattern_set_filter(pattern,
                           sampler.mag_filter == 9728 ? CAIRO_FILTER_NEAREST : CAIRO_FILTER_GOOD);
  return pattern;
}

// The texture through `matrix` as the source.
void set_texture_source(cairo_t* cr, const PrintTexture& tex, const cairo_matrix_t& matrix) {
  cairo_pattern_t* pattern = sampled(tex.surface.get(), tex.sampler, matrix);
  cairo_set_source(cr, pattern);
  cairo_pattern_destroy(pattern);
}

// Fills each part from the texture.
void fill_texture(cairo_t* cr, const PrintTexture& tex, const std::vector<TexturePart>& parts) {
  for (const TexturePart& part : parts) {
    set_texture_source(cr, tex, part.matrix);
    trace(cr, part.outline);
    cairo_fill(cr);
  }
}

// The texture at the centroid of uv, for a triangle whose map to the texture is degenerate
// (a point or a line): sampled as the pattern would, bilinearly between the four texels around
// it (nearest under a nearest filter), each wrapped by the sampler.
std::array<double, 3> texel_at(const PrintTexture& tex, const std::array<UV, 3>& uv) {
  auto wrap = [](double x, int n, int mode) {  // texel index x (whole) into [0, n)
    if (mode == 33071) return static_cast<int>(std::clamp(x, 0.0, n - 1.0));
    const double period = mode == 33648 ? 2.0 * n : n;
    double i = std::fmod(x, period);
    if (i < 0) i += period;
    const int k = std::clamp(static_cast<int>(i), 0, static_cast<int>(period) - 1);
    return k >= n ? 2 * n - 1 - k : k;
  };
  const double u = uv[0][0] / 3 + uv[1][0] / 3 + uv[2][0] / 3;
  const double v = uv[0][1] / 3 + uv[1][1] / 3 + uv[2][1] / 3;
  cairo_surface_t* s = tex.surface.get();
  auto texel = [&](double x, double y) {
    const int ix = wrap(x, tex.width, tex.sampler.wrap_s);
    const int iy = wrap(y, tex.height, tex.sampler.wrap_t);
    const auto* row = reinterpret_cast<const std::uint32_t*>(cairo_image_surface_get_data(s) +
                                                             static_cast<std::ptrdiff_t>(iy) *
                                                                 cairo_image_surface_get_stride(s));
    const std::uint32_t px = row[ix];
    return std::array<double, 3>{((px >> 16) & 255) / 255.0, ((px >> 8) & 255) / 255.0,
                                 (px & 255) / 255.0};
  };
  if (tex.sampler.mag_filter == 9728)
    return texel(std::floor(u * tex.width), std::floor(v * tex.height));
  // Texel centres at half-integers.
  const double x = u * tex.width - 0.5, y = v * tex.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
  const auto a = texel(x0, y0), b = texel(x0 + 1, y0), c = texel(x0, y0 + 1),
             d = texel(x0 + 1, y0 + 1);
  std::array<double, 3> out;
  for (int i = 0; i < 3; ++i)
    out[i] = (1 - fy) * ((1 - fx) * a[i] + fx * b[i]) + fy * ((1 - fx) * c[i] + fx * d[i]);
  return out;
}

// Triangle p grown by `d` on every side: each corner moved out along its bisector by d over the
// sine of its half angle (at most 4 d, so a sliver's sharp corner stays near). Filled instead of
// p, it covers the hairline antialiasing leaves between neighbouring triangles and reaches d past
// the cuts; a stroke would do the same at several times the cost.
std::vector<Vec2> grown(std::array<Vec2, 3> p, double d) {
  if (cross(p[1] - p[0], p[2] - p[0]) < 0) std::swap(p[1], p[2]);  // all one orientation
  std::vector<Vec2> out(p.begin(), p.end());
  for (int i = 0; i < 3; ++i) {
    const Vec2 a = p[(i + 2) % 3], v = p[i], b = p[(i + 1) % 3];
    const double la = norm(v - a), lb = norm(v - b);
    if (!(la > 0 && lb > 0)) continue;
    const Vec2 u = (1 / la) * (v - a), w = (1 / lb) * (v - b);
    const Vec2 bisector = u + w;
    const double n = norm(bisector);
    if (!(n > 1e-12)) continue;
    // sin(half angle) = |u + w| / 2 for unit u, w pointing out of the corner's sides.
    const double reach = std::min(4 * d, 2 * d / n);
    out[i] = v + (reach / n) * bisector;
  }
  return out;
}

// sRGB of a linear value, by table (16,384 steps: at most 0.2/255 off, near black where the
// curve is steepest), for colour computed pixel by pixel.
double srgb_by_table(double linear) {
  constexpr std::size_t kSteps = 16384;
  static const std::vector<float> table = [] {
    std::vector<float> t(kSteps);
    for (std::size_t i = 0; i < kSteps; ++i)
      t[i] = static_cast<float>(srgb(static_cast<double>(i) / (kSteps - 1)));
    return t;
  }();
  const double c = std::clamp(linear, 0.0, 1.0);
  return table[static_cast<std::size_t>(c * (kSteps - 1) + 0.5)];
}

// The vertex colours of t (no texture) written straight into the pixels of cr's image whose
// centres lie inside the convex polygons `outline` (user space), opaque: each pixel the colour
// of t placed at p at its centre, interpolated linear and turned into sRGB there, extended past
// p over the bleed. It draws what the bleed fill and the mesh gradient draw, at a fraction of
// the cost: cairo rasterises a mesh pattern by subdividing its patches to pixel size (the Menger
// sponge's 77 pages at 300 dpi took 26 s with cairo's gradients, 19 s so). Only without
// antialiasing, where the two agree pixel for pixel but for the bleed's colour; false,
// drawing nothing, where the target is not such an image.
bool write_gradient(cairo_t* cr, const ColourTriangle& t, const std::array<Vec2, 3>& p,
                    const Outline& outline, const PrintColour& colour) {
  cairo_surface_t* target = cairo_get_target(cr);
  if (cairo_get_antialias(cr) != CAIRO_ANTIALIAS_NONE ||
      cairo_surface_get_type(target) != CAIRO_SURFACE_TYPE_IMAGE ||
      cairo_image_surface_get_format(target) != CAIRO_FORMAT_ARGB32)
    return false;
  const auto device = [&](Vec2 q) {
    cairo_user_to_device(cr, &q.x, &q.y);
    return q;
  };
  const std::array<Vec2, 3> d{device(p[0]), device(p[1]), device(p[2])};
  const double det = cross(d[1] - d[0], d[2] - d[0]);
  if (!(std::abs(det) > 1e-12)) return false;
  // Each channel's linear value is affine on the page: value(x, y) = at0 + dx x + dy y.
  const std::array<double, 3> c0 = linear_factor_at(t, colour, {1, 0, 0}),
                              c1 = linear_factor_at(t, colour, {0, 1, 0}),
                              c2 = linear_factor_at(t, colour, {0, 0, 1});
  std::array<double, 3> at0{}, dx{}, dy{};
  for (int i = 0; i < 3; ++i) {
    const double v0 = c0[i];
    // v(q) = v0 + u (v1 - v0) + w (v2 - v0), u and w q's weights of corners 1 and 2.
    const double a = c1[i] - v0, b = c2[i] - v0;
    dx[i] = (a * (d[2].y - d[0].y) - b * (d[1].y - d[0].y)) / det;
    dy[i] = (b * (d[1].x - d[0].x) - a * (d[2].x - d[0].x)) / det;
    at0[i] = v0 - dx[i] * d[0].x - dy[i] * d[0].y;
  }
  const double cover = factor_cover(t, colour);
  const int width = cairo_image_surface_get_width(target);
  const int height = cairo_image_surface_get_height(target);
  const int stride = cairo_image_surface_get_stride(target);
  cairo_surface_flush(target);
  unsigned char* data = cairo_image_surface_get_data(target);
  if (!data) return false;
  for (const auto& polygon : outline) {
    std::vector<Vec2> q;
    for (const Vec2 v : polygon) q.push_back(device(v));
    double top = INFINITY, bottom = -INFINITY;
    for (const Vec2 v : q) top = std::min(top, v.y), bottom = std::max(bottom, v.y);
    if (!(top <= bottom)) continue;  // not finite
    const int y0 = static_cast<int>(std::clamp(std::ceil(top - 0.5), 0.0, double(height)));
    const int y1 = static_cast<int>(std::clamp(std::floor(bottom - 0.5), -1.0, height - 1.0));
    for (int y = y0; y <= y1; ++y) {
      // The row's span inside the convex polygon, at the pixels' centres.
      const double yc = y + 0.5;
      double left = INFINITY, right = -INFINITY;
      for (std::size_t k = 0; k < q.size(); ++k) {
        const Vec2 a = q[k], b = q[(k + 1) % q.size()];
        if ((a.y <= yc) == (b.y <= yc)) continue;
        const double x = a.x + (yc - a.y) * (b.x - a.x) / (b.y - a.y);
        left = std::min(left, x), right = std::max(right, x);
      }
      if (!(left <= right)) continue;  // the row only touches a corner
      const int x0 = static_cast<int>(std::clamp(std::ceil(left - 0.5), 0.0, double(width)));
      const int x1 = static_cast<int>(std::clamp(std::floor(right - 0.5), -1.0, width - 1.0));
      auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
      for (int x = x0; x <= x1; ++x) {
        std::uint32_t pixel = 0xff000000u;
        for (int i = 0; i < 3; ++i) {
          const double s = srgb_by_table(at0[i] + dx[i] * (x + 0.5) + dy[i] * yc);
          const double v = s * cover + (1 - cover);
          pixel |= static_cast<std::uint32_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255))
                   << (16 - 8 * i);
        }
        row[x] = pixel;
      }
    }
  }
  cairo_surface_mark_dirty(target);
  return true;
}

// Fills the triangles at page corners ps with the colour of t placed at ps[0] (those after it
// share its map: placed parts of one face coloured from one source face), and `bleed`
// millimetres around them; with `area`, that polygon instead, coloured by the triangle's map
// extended past its sides.
void paint(cairo_t* cr, const ColourTriangle& t, const std::vector<std::array<Vec2, 3>>& ps,
           const PrintColour& colour, double bleed, const std::vector<Vec2>* area = nullptr) {
  const std::array<Vec2, 3>& p = ps.front();
  const std::array<std::array<double, 3>, 3> c{
      corner_colour(t, colour, 0), corner_colour(t, colour, 1), corner_colour(t, colour, 2)};
  const bool uniform = c[0] == c[1] && c[1] == c[2];
  const bool white = uniform && c[0] == std::array<double, 3>{1, 1, 1};
  const PrintTexture* tex = texture_of(t, colour);
  Outline outline;
  if (area) outline.push_back(*area);
  for (std::size_t i = 0; !area && i < ps.size(); ++i) outline.push_back(grown(ps[i], bleed));
  const std::vector<TexturePart> parts =
      tex ? texture_parts(*tex, p, t.uv, outline) : std::vector<TexturePart>{};
  auto fill_and_bleed = [&] {
    trace(cr, outline);
    cairo_fill(cr);
  };
  if (tex && parts.empty()) {  // squeezed to a point or a line, or repeated too often
    const auto texel = texel_at(*tex, t.uv);
    cairo_set_source_rgb(cr, texel[0] * c[0][0], texel[1] * c[0][1], texel[2] * c[0][2]);
    fill_and_bleed();
    return;
  }
  // The paper showing through a Mask or Blend material (docs/colour.md, "Alpha"): the texture's
  // alpha, times the factor's cover. Drawn for a texture taken through one map.
  const SurfacePtr alpha =
      tex && t.material >= 0 && t.material < static_cast<int>(colour.alpha.size())
          ? colour.alpha[t.material]
          : nullptr;
  // Under Mask the alpha image already holds the factor's alpha (print_colour).
  const bool masked = alpha && colour.materials[t.material].alpha_mode == AlphaMode::Mask;
  const double cover = masked ? 1.0 : factor_cover(t, colour);
  const bool see_through = tex && parts.size() == 1 && (alpha || cover < 1);
  if (tex && white && parts.size() == 1 && !see_through) {
    fill_texture(cr, *tex, parts);
    return;
  }
  auto gradient = [&] {
    cairo_pattern_t* mesh = cairo_pattern_create_mesh();
    const int n = gradient_steps(c);
    auto patch = [&](std::array<std::array<int, 2>, 3> ij) {
      cairo_mesh_pattern_begin_patch(mesh);
      for (int k = 0; k < 3; ++k) {
        const double b = double(ij[k][0]) / n, g = double(ij[k][1]) / n;
        const std::array<double, 3> w{1 - b - g, b, g};
        const Vec2 q = w[0] * p[0] + w[1] * p[1] + w[2] * p[2];
        if (k == 0)
          cairo_mesh_pattern_move_to(mesh, q.x, q.y);
        else
          cairo_mesh_pattern_line_to(mesh, q.x, q.y);
        const auto rgb = factor_at(t, colour, w);
        cairo_mesh_pattern_set_corner_color_rgb(mesh, k, rgb[0], rgb[1], rgb[2]);
      }
      cairo_mesh_pattern_end_patch(mesh);
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        patch({{{i, j}, {i + 1, j}, {i, j + 1}}});
        if (i + j + 1 < n) patch({{{i + 1, j}, {i + 1, j + 1}, {i, j + 1}}});
      }
    return mesh;
  };
  // The bleed in the colour of the corners' mean; a gradient only covers its triangle.
  auto mean = [&](int i) { return (c[0][i] + c[1][i] + c[2][i]) / 3; };
  if (!tex && !uniform && !area && write_gradient(cr, t, p, outline, colour)) return;
  if (!tex) {
    cairo_set_source_rgb(cr, mean(0), mean(1), mean(2));
    fill_and_bleed();
    if (!uniform) {
      // Over a tab (`area`), only where the tab is: the triangle placed hinged may reach past it.
      cairo_save(cr);
      if (area) {
        trace(cr, outline);
        cairo_clip(cr);
      }
      cairo_pattern_t* mesh = gradient();
      cairo_set_source(cr, mesh);
      cairo_pattern_destroy(mesh);
      trace(cr, p);
      cairo_fill(cr);
      cairo_restore(cr);
    }
    return;
  }
  // Texture times colour: the product made in a group over the triangle, then drawn.
  cairo_save(cr);
  trace(cr, outline);
  double x0, y0, x1, y1;
  cairo_fill_extents(cr, &x0, &y0, &x1, &y1);
  cairo_new_path(cr);
  cairo_rectangle(cr, x0, y0, x1 - x0, y1 - y0);
  cairo_clip(cr);
  cairo_push_group(cr);
  if (parts.size() == 1) {
    set_texture_source(cr, *tex, parts[0].matrix);
    cairo_paint(cr);
  } else {  // under the parts' seams: the texel at the centre
    const auto texel = texel_at(*tex, t.uv);
    cairo_set_source_rgb(cr, texel[0], texel[1], texel[2]);
    cairo_paint(cr);
    fill_texture(cr, *tex, parts);
  }
  cairo_set_operator(cr, CAIRO_OPERATOR_MULTIPLY);
  if (uniform) {
    cairo_set_source_rgb(cr, c[0][0], c[0][1], c[0][2]);
    cairo_paint(cr);
  } else {  // the gradient covers the triangle only: its bleed keeps the texture's colour
    cairo_pattern_t* mesh = gradient();
    cairo_set_source(cr, mesh);
    cairo_pattern_destroy(mesh);
    trace(cr, p);
    cairo_fill(cr);
  }
  if (!see_through) {
    cairo_pop_group_to_source(cr);
    fill_and_bleed();
    cairo_restore(cr);
    return;
  }
  // The paper, then the product through the alpha.
  cairo_pattern_t* product = cairo_pop_group(cr);
  cairo_set_source_rgb(cr, 1, 1, 1);
  trace(cr, outline);
  cairo_fill_preserve(cr);
  cairo_clip(cr);
  cairo_set_source(cr, product);
  cairo_pattern_destroy(product);
  if (!alpha) {
    cairo_paint_with_alpha(cr, cover);
  } else {
    cairo_pattern_t* through = sampled(alpha.get(), tex->sampler, parts[0].matrix);
    if (cover < 1) {  // the factor's alpha times the texture's
      cairo_push_group_with_content(cr, CAIRO_CONTENT_ALPHA);
      cairo_set_source(cr, through);
      cairo_paint_with_alpha(cr, cover);
      cairo_pattern_destroy(through);
      through = cairo_pop_group(cr);
    }
    cairo_mask(cr, through);
    cairo_pattern_destroy(through);
  }
  cairo_restore(cr);
}

// Page corners of a colour triangle of a face placed at page corners f.
std::array<Vec2, 3> place(const ColourTriangle& t, const std::array<Vec2, 3>& f) {
  std::array<Vec2, 3> p;
  for (int k = 0; k < 3; ++k) p[k] = t.at[k][0] * f[0] + t.at[k][1] * f[1] + t.at[k][2] * f[2];
  return p;
}

// The rigid motion of the plane that takes a0 to a1 and b0 to b1 (|a0 b0| = |a1 b1|).
struct Motion {
  Vec2 from, to;
  double c = 1, s = 0;
  Vec2 operator()(Vec2 p) const {
    const Vec2 d = p - from;
    return to + Vec2{c * d.x - s * d.y, s * d.x + c * d.y};
  }
};
Motion motion(Vec2 a0, Vec2 b0, Vec2 a1, Vec2 b1) {
  const Vec2 u = b0 - a0, v = b1 - a1;
  const double n = norm(u) * norm(v);
  if (!(n > 0)) return {a0, a1, 1, 0};
  return {a0, a1, dot(u, v) / n, cross(u, v) / n};
}

}  // namespace

bool PrintColour::any() const {
  for (const auto& f : faces)
    for (const ColourTriangle& t : f)
      if (coloured(t, *this)) return true;
  return false;
}

PrintColour print_colour(const MeshColour& colour, std::size_t faces, double dpi,
                         std::vector<PrintNote>& notes) {
  PrintColour out;
  out.dpi = dpi;
  out.materials = colour.materials;
  out.alpha.resize(out.materials.size());
  for (const Texture& t : colour.textures) {
    PrintTexture& p = out.textures.emplace_back();
    p.sampler = t.sampler;
    try {
      const Image image = decode_image(t.bytes);
      p.surface = texture_surface(image);
      p.width = image.width;
      p.height = image.height;
      const int k = static_cast<int>(out.textures.size()) - 1;
      for (std::size_t m = 0; m < out.materials.size(); ++m) {
        const Material& material = out.materials[m];
        if (material.texture != k || material.alpha_mode == AlphaMode::Opaque) continue;
        const bool mask = material.alpha_mode == AlphaMode::Mask;
        out.alpha[m] = alpha_surface(image, material.base_color[3],
                                     mask ? std::max(material.alpha_cutoff, 0.0) : -1.0);
      }
    } catch (const IOException& e) {
      notes.push_back({"texture_not_printed", 1,
                       "texture " + std::to_string(out.textures.size() - 1) +
                           (t.name.empty() ? std::string() : " (" + t.name + ")") +
                           " is printed without its image: " + e.what()});
    }
  }
  if (colour.empty()) return out;
  out.faces.resize(faces);
  std::size_t unmapped = 0, far = 0;
  for (std::size_t f = 0; f < faces; ++f) {
    ColourTriangle t;
    if (f < colour.uvs.size()) t.uv = colour.uvs[f];
    if (f < colour.colours.size()) t.rgba = colour.colours[f];
    if (f < colour.face_materials.size()) t.material = colour.face_materials[f];
    if (coloured(t, out)) out.faces[f].push_back(t);
    // A face whose material has a decoded texture: are its coordinates usable?
    const int m = t.material;
    const int k =
        m >= 0 && m < static_cast<int>(out.materials.size()) ? out.materials[m].texture : -1;
    if (k < 0 || k >= static_cast<int>(out.textures.size()) || !out.textures[k].surface) continue;
    if (!texture_of(t, out)) {
      ++unmapped;
    } else if (out.textures[k].sampler.wrap_s == 33071) {
      for (const UV& uv : t.uv)
        if (std::abs(uv[0] - 0.5) > 0.5 + kNearUv || std::abs(uv[1] - 0.5) > 0.5 + kNearUv) {
          ++far;
          break;
        }
    }
  }
  if (unmapped > 0)
    notes.push_back({"texture_coordinates_missing", unmapped,
                     std::to_string(unmapped) +
                         " textured faces have no finite texture coordinates (NaN, infinite or "
                         "missing): they print in their material's colour without the texture"});
  if (far > 0)
    notes.push_back({"texture_coordinates_out_of_range", far,
                     std::to_string(far) + " faces have texture coordinates more than " +
                         std::to_string(static_cast<int>(kNearUv)) +
                         " texture widths outside [0, 1] under clamp sampling: they print the "
                         "colours of the texture's edge, as clamping says, which is seldom what "
                         "the model meant"});
  return out;
}

namespace {

// A tab glues under the face across its edge: it shows that face hinged onto the tab's side.
struct TabUnder {
  const Tab* tab;
  int under;
};

// The pieces of a layout (faces joined by folds) with colour, each by the index of one of its
// faces: its coloured faces, the tabs that show a coloured face, and the box of both on the page
// (`map` takes a layout point there).
struct ColouredPieces {
  std::vector<char> has_colour;
  std::vector<std::vector<int>> members;
  std::vector<std::vector<TabUnder>> tabs;
  std::vector<Box2> box;
};

template <class Map>
ColouredPieces coloured_pieces(const PrintLayout& layout, const PrintColour& colour, Map map) {
  const std::size_t n = layout.faces.size();
  UnionFind pieces(n);
  for (const NetEdge& e : layout.edges)
    if (e.kind != EdgeKind::Cut && e.b.face >= 0) pieces.unite(e.a.face, e.b.face);
  ColouredPieces out{std::vector<char>(n, 0), std::vector<std::vector<int>>(n),
                     std::vector<std::vector<TabUnder>>(n), std::vector<Box2>(n, Box2::empty())};
  for (std::size_t f = 0; f < n; ++f) {
    if (colour.faces[f].empty()) continue;
    const int r = pieces.find(static_cast<int>(f));
    out.has_colour[r] = 1;
    out.members[r].push_back(static_cast<int>(f));
    for (Vec2 p : layout.faces[f]) out.box[r].add(map(p));
  }
  for (const Tab& tab : layout.tabs) {
    const NetEdge& e = layout.edges[tab.edge];
    const int under = e.a.face == tab.side.face ? e.b.face : e.a.face;
    if (under < 0 || colour.faces[under].empty()) continue;
    const int r = pieces.find(tab.side.face);
    out.tabs[r].push_back({&tab, under});
    out.has_colour[r] = 1;
    for (Vec2 p : tab.corners) out.box[r].add(map(p));
  }
  return out;
}

}  // namespace

std::vector<double> colour_image_areas(const PrintLayout& layout, const PrintColour& colour) {
  std::vector<double> areas;
  if (colour.faces.size() != layout.faces.size()) return areas;
  const ColouredPieces coloured = coloured_pieces(layout, colour, [](Vec2 p) { return p; });
  for (std::size_t r = 0; r < coloured.box.size(); ++r)
    if (coloured.has_colour[r]) {
      const Vec2 size = coloured.box[r].size();
      areas.push_back(size.x * size.y);
    }
  return areas;
}

double colour_images_pixels(const std::vector<double>& areas, double dpi) {
  const double per_mm2 = (dpi / 25.4) * (dpi / 25.4);
  double pixels = 0;
  for (double area : areas) pixels += std::min(area * per_mm2, kMaxImagePixels);
  return pixels;
}

std::vector<PageImage> colour_images(const PrintLayout& layout, const PrintColour& colour, Vec2 lo,
                                     Vec2 hi, Vec2 at, Vec2 clip_lo, Vec2 clip_hi) {
  std::vector<PageImage> images;
  const std::size_t n = layout.faces.size();
  if (colour.faces.size() != n) return images;
  auto map = [&](Vec2 p) { return Vec2{at.x + (p.x - lo.x), at.y + (hi.y - p.y)}; };
  auto page_face = [&](int f) {
    const auto& t = layout.faces[f];
    return std::array<Vec2, 3>{map(t[0]), map(t[1]), map(t[2])};
  };
  const auto [has_colour, members, tabs, box] = coloured_pieces(layout, colour, map);
  const double px_per_mm = colour.dpi / 25.4;
  const double bleed = 1 / px_per_mm;
  for (std::size_t r = 0; r < n; ++r) {
    if (!has_colour[r]) continue;
    Box2 b = box[r];
    b.lo = {std::max(b.lo.x - 2 * bleed, clip_lo.x), std::max(b.lo.y - 2 * bleed, clip_lo.y)};
    b.hi = {std::min(b.hi.x + 2 * bleed, clip_hi.x), std::min(b.hi.y + 2 * bleed, clip_hi.y)};
    if (!(b.hi.x > b.lo.x && b.hi.y > b.lo.y)) continue;
    // Whole pixels from the box's corner, at most kMaxImagePixels.
    const double scale =
        std::min(px_per_mm, std::sqrt(kMaxImagePixels / ((b.hi.x - b.lo.x) * (b.hi.y - b.lo.y))));
    const int w = std::max(1, static_cast<int>(std::ceil((b.hi.x - b.lo.x) * scale)));
    const int h = std::max(1, static_cast<int>(std::ceil((b.hi.y - b.lo.y) * scale)));
    SurfacePtr surface = own(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h));
    if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
      throw IOException("cairo could not make a " + std::to_string(w) + " x " + std::to_string(h) +
                        " colour image");
    cairo_t* cr = cairo_create(surface.get());
    // A pixel no wider than half a cut line (0.125 mm): the colour's edges, a pixel past the
    // cuts, lie under the line art, and neighbouring triangles overlap by their bleed, so
    // antialiasing would show nowhere; without it cairo fills about a quarter faster.
    if (scale >= 8) cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
    cairo_scale(cr, scale, scale);
    cairo_translate(cr, -b.lo.x, -b.lo.y);
    const double line = 1 / scale;  // the bleed: a pixel at the resolution drawn
    // What is painted for a triangle lies within 4 bleeds of it (`grown`), antialiasing a pixel
    // more: a face or tab whose box stays 8 pixels off the image paints none of its pixels, and
    // is passed over. Only a piece cut by the page's clip has such parts: a tiled net's piece,
    // which spans many pages, and would otherwise be painted whole on each of them.
    const Box2 image{{b.lo.x - 8 * line, b.lo.y - 8 * line},
                     {b.lo.x + (w + 8) * line, b.lo.y + (h + 8) * line}};
    bool drawn = false;  // a face or tab painted: an image without any is left out
    const auto off_image = [&](const Box2& box) {
      const bool off = !boxes_overlap(box, image, 0);
      drawn = drawn || !off;
      return off;
    };
    for (int f : members[r]) {
      const auto corners = page_face(f);
      // Triangles coloured from one source face share its map: one fill for them all.
      const auto& triangles = colour.faces[f];
      if (off_image(triangle_box(corners))) continue;  // its triangles are parts of it
      std::vector<std::size_t> order(triangles.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      auto key = [&](std::size_t i) {
        const ColourTriangle& t = triangles[i];
        return t.source >= 0 && !finite(t.rgba[0]) ? t.source : -1 - static_cast<long>(i);
      };
      std::stable_sort(order.begin(), order.end(),
                       [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
      // The group's map is taken from its largest triangle (a sliver's is ill-conditioned),
      // which goes first.
      std::vector<std::array<Vec2, 3>> group;
      std::size_t largest = 0;
      double area = -1;
      for (std::size_t i = 0; i < order.size(); ++i) {
        const auto placed = place(triangles[order[i]], corners);
        const double a = std::abs(cross(placed[1] - placed[0], placed[2] - placed[0]));
        group.push_back(placed);
        if (a > area) {
          area = a, largest = order[i];
          std::swap(group.front(), group.back());
        }
        if (i + 1 < order.size() && key(order[i + 1]) == key(order[i])) continue;
        paint(cr, triangles[largest], group, colour, line);
        group.clear();
        area = -1;
      }
    }
    for (const TabUnder& tu : tabs[r]) {
      const NetEdge& e = layout.edges[tu.tab->edge];
      const EdgeSide& own_side = e.a.face == tu.tab->side.face ? e.a : e.b;
      const EdgeSide& under_side = e.a.face == tu.tab->side.face ? e.b : e.a;
      const auto mine = page_face(own_side.face), under = page_face(under_side.face);
      // The edge runs k -> k+1 on one side and k+1 -> k on the other.
      const Motion hinge = motion(under[under_side.k], under[(under_side.k + 1) % 3],
                                  mine[(own_side.k + 1) % 3], mine[own_side.k]);
      const std::array<Vec2, 3> hinged{hinge(under[0]), hinge(under[1]), hinge(under[2])};
      std::vector<Vec2> tab;
      Box2 painted = Box2::empty();
      for (Vec2 q : tu.tab->corners) tab.push_back(map(q)), painted.add(tab.back());
      if (off_image(painted)) continue;
      // The tab shows the under face's triangle nearest the edge's middle, its map extended
      // over the whole tab (a tab can reach past that triangle, and past its face).
      const Vec2 middle = 0.5 * (mine[own_side.k] + mine[(own_side.k + 1) % 3]);
      const auto& under_triangles = colour.faces[tu.under];
      std::size_t nearest = 0;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < under_triangles.size(); ++i) {
        const auto q = place(under_triangles[i], hinged);
        const double d = norm((1.0 / 3) * (q[0] + q[1] + q[2]) - middle);
        if (d < best) best = d, nearest = i;
      }
      paint(cr, under_triangles[nearest], {place(under_triangles[nearest], hinged)}, colour, line,
            &tab);
    }
    const cairo_status_t status = cairo_status(cr);
    cairo_destroy(cr);
    if (status != CAIRO_STATUS_SUCCESS)
      throw IOException(std::string("cairo failed drawing colour: ") +
                        cairo_status_to_string(status));
    if (drawn) images.push_back({b.lo, w / scale, h / scale, std::move(surface)});
  }
  return images;
}

namespace {
cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}
}  // namespace

std::string encode_png(cairo_surface_t* surface) {
  std::string out;
  const cairo_status_t status = cairo_surface_write_to_png_stream(surface, append, &out);
  if (status != CAIRO_STATUS_SUCCESS)
    throw IOException(std::string("cairo could not write a PNG: ") +
                      cairo_status_to_string(status));
  return out;
}

}  // namespace papernet
