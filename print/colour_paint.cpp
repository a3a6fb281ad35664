// One colour triangle painted on a piece's image (print/internal/colour_draw.h): its texture,
// its vertex colours as a gradient (linear, as glTF has them) and its material's factor
// multiplied (CAIRO_OPERATOR_MULTIPLY), the paper showing through its alpha, about a pixel of
// bleed around it.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "print/internal/colour_draw.h"

namespace papernet::print_detail {
namespace {

// glTF's factors and vertex colours are linear; textures and paper are sRGB.
double srgb(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

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

}  // namespace

// Fills the triangles at page corners ps with the colour of t placed at ps[0] (those after it
// share its map: placed parts of one face coloured from one source face), and `bleed`
// millimetres around them; with `area`, that polygon instead, coloured by the triangle's map
// extended past its sides.
void paint(cairo_t* cr, const ColourTriangle& t, const std::vector<std::array<Vec2, 3>>& ps,
           const PrintColour& colour, double bleed, const std::vector<Vec2>* area) {
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

}  // namespace papernet::print_detail
