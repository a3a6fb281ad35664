// The texture through a colour triangle's map from the page to its texels
// (print/internal/colour_draw.h): the parts of a polygon to fill, each through one matrix that
// keeps its texel coordinates within what pixman holds, and the texel of a degenerate map.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "print/internal/colour_draw.h"

namespace papernet::print_detail {
namespace {

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

}  // namespace

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

cairo_pattern_t* sampled(cairo_surface_t* surface, const TextureSampler& sampler,
                         const cairo_matrix_t& matrix) {
  cairo_pattern_t* pattern = cairo_pattern_create_for_surface(surface);
  cairo_pattern_set_matrix(pattern, &matrix);
  cairo_pattern_set_extend(pattern, extend_of(sampler.wrap_s));
  cairo_pattern_set_filter(pattern,
                           sampler.mag_filter == 9728 ? CAIRO_FILTER_NEAREST : CAIRO_FILTER_GOOD);
  return pattern;
}

void set_texture_source(cairo_t* cr, const PrintTexture& tex, const cairo_matrix_t& matrix) {
  cairo_pattern_t* pattern = sampled(tex.surface.get(), tex.sampler, matrix);
  cairo_set_source(cr, pattern);
  cairo_pattern_destroy(pattern);
}

void fill_texture(cairo_t* cr, const PrintTexture& tex, const std::vector<TexturePart>& parts) {
  for (const TexturePart& part : parts) {
    set_texture_source(cr, tex, part.matrix);
    trace(cr, part.outline);
    cairo_fill(cr);
  }
}

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

}  // namespace papernet::print_detail
