// The model's colour printed (docs/colour.md, "Printing"): its textures decoded for cairo, and
// each coloured piece rasterised into an image of its own, face by face and tab by tab
// (print/colour_paint.cpp paints each colour triangle), about a pixel of bleed past its cuts.
#include "print/colour.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/io/image.h"
#include "core/unfold/overlap.h"
#include "core/union_find.h"
#include "print/internal/colour_draw.h"

namespace papernet {

using print_detail::finite;
using print_detail::kNearUv;
using print_detail::own;
using print_detail::paint;
using print_detail::SurfacePtr;
using print_detail::texture_of;

namespace print_detail {

const PrintTexture* texture_of(const ColourTriangle& t, const PrintColour& colour) {
  if (t.material < 0 || t.material >= static_cast<int>(colour.materials.size())) return nullptr;
  const int k = colour.materials[t.material].texture;
  if (k < 0 || k >= static_cast<int>(colour.textures.size())) return nullptr;
  const PrintTexture& tex = colour.textures[k];
  if (!tex.surface || !finite(t.uv[0]) || !finite(t.uv[1]) || !finite(t.uv[2])) return nullptr;
  return &tex;
}

}  // namespace print_detail

namespace {

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

bool coloured(const ColourTriangle& t, const PrintColour& colour) {
  return texture_of(t, colour) ||
         (t.material >= 0 && t.material < static_cast<int>(colour.materials.size())) ||
         (finite(t.rgba[0]) && finite(t.rgba[1]) && finite(t.rgba[2]));
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