// The model as built, for the overview page (docs/print.md, "The overview page"). cairo paints
// the faces far to near (the painter's algorithm), the backs of faces before the fronts and large
// faces in fragments of at most kFragmentMm, each at its own depth; once shaded for the page and
// once without smoothing, each fragment its piece's index, to read which piece shows at each
// point: the numbers go where their piece shows most.
#include "print/model_view.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>

#include "core/mesh/dual_graph.h"
#include "print/internal/page_boxes.h"
#include "print/layout.h"

namespace papernet {
namespace {

using SurfacePtr = std::shared_ptr<cairo_surface_t>;

Vec3 unit(Vec3 v) {
  const double n = norm(v);
  return n > 0 ? (1 / n) * v : v;
}

// The item image's pixels per millimetre: a 2 mm number spans 8 of them.
constexpr double kItemsPerMm = 4;
// The shaded image is painted this many times finer, then scaled down (shade).
constexpr int kSupersample = 3;
// The share of a number's box that must show its piece.
constexpr double kOnPiece = 0.9;
// A piece showing at least this many pixels (a square millimetre) but too little for its number
// on it gets the number beside the model with a line to it, on rings of text boxes around it out
// to this many (about 30 mm at 2.5 mm).
constexpr std::size_t kLeaderPixels = 16;
constexpr int kLeaderRings = 12;
// How far such a line may run over other pieces, mm: a longer one reads as pointing at them.
constexpr double kLeaderAcrossMm = 3;

/// A light colour of its own for piece `p`: hues a golden angle apart, so that pieces numbered
/// one after the other (neighbours, in build order) differ most.
std::array<double, 3> piece_rgb(int p) {
  const double h = std::fmod(0.58 + 0.618033988749895 * p, 1.0) * 6;
  const double s = 0.38, v = 0.97;
  const double f = h - std::floor(h);
  const double a = v * (1 - s), b = v * (1 - s * f), c = v * (1 - s * (1 - f));
  switch (static_cast<int>(h) % 6) {
    case 0:
      return {v, c, a};
    case 1:
      return {b, v, a};
    case 2:
      return {a, v, c};
    case 3:
      return {a, b, v};
    case 4:
      return {c, a, v};
    default:
      return {v, a, b};
  }
}

/// The mesh seen along -toward: each vertex on the page (mm, y down) and its depth (larger:
/// nearer).
struct Projection {
  std::vector<Vec2> at;
  std::vector<double> depth;
};

Projection project(const Mesh& mesh, Vec3 toward, Vec3 up, Vec2 lo, Vec2 hi) {
  const Vec3 w = unit(toward);
  const Vec3 x = unit(cross(up, w));
  const Vec3 y = cross(w, x);
  Projection p;
  Box2 box = Box2::empty();
  for (const Vec3& v : mesh.vertices) {
    p.at.push_back({dot(v, x), dot(v, y)});
    p.depth.push_back(dot(v, w));
    box.add(p.at.back());
  }
  const Vec2 size = box.size(), room = hi - lo;
  const double s = std::min(size.x > 0 ? room.x / size.x : 1, size.y > 0 ? room.y / size.y : 1);
  const Vec2 offset = 0.5 * (room - s * size);
  for (Vec2& a : p.at)
    a = {lo.x + offset.x + s * (a.x - box.lo.x), hi.y - offset.y - s * (a.y - box.lo.y)};
  return p;
}

/// For each face, which of its sides part it from another piece (or border a hole): bit k for
/// the side from corner k to corner k + 1.
std::vector<std::uint8_t> piece_borders(const Mesh& mesh, std::span<const int> piece) {
  std::unordered_map<std::uint64_t, std::vector<int>> faces_of;  // by the side's two vertices
  const auto key = [&](std::size_t f, int k) {
    return edge_key(mesh.faces[f][k], mesh.faces[f][(k + 1) % 3]);
  };
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) faces_of[key(f, k)].push_back(static_cast<int>(f));
  std::vector<std::uint8_t> out(mesh.faces.size(), 0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto& across = faces_of[key(f, k)];
      const bool border =
          across.size() != 2 ||
          std::any_of(across.begin(), across.end(), [&](int g) { return piece[g] != piece[f]; });
      if (border) out[f] |= static_cast<std::uint8_t>(1u << k);
    }
  return out;
}

// The longest side of a piece of a face as painted, mm: a large face is painted in smaller
// pieces, each at its own depth, so that its far end goes under what is in front of it.
constexpr double kFragmentMm = 2;

/// A piece of a face as painted: its corners on the page, its depth, which of its sides lie on
/// a border of the face's piece (bit k: from corner k to k + 1).
struct Fragment {
  std::array<Vec2, 3> at;
  std::array<double, 3> depth;
  int face = 0;
  std::uint8_t borders = 0;
  bool front = true;
};

/// The faces in fragments, in the order they are painted: the backs of faces (seen inside an
/// open model) first, then the fronts, each far to near by the depths of their centres.
std::vector<Fragment> paint_order(const Mesh& mesh, std::span<const int> piece, const Projection& p,
                                  Vec3 toward) {
  const std::vector<std::uint8_t> borders = piece_borders(mesh, piece);
  const Vec3 w = unit(toward);
  std::vector<Fragment> out, todo;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    todo.push_back({{p.at[t[0]], p.at[t[1]], p.at[t[2]]},
                    {p.depth[t[0]], p.depth[t[1]], p.depth[t[2]]},
                    static_cast<int>(f),
                    borders[f],
                    dot(face_normal(mesh, static_cast<int>(f)), w) >= 0});
    while (!todo.empty()) {
      Fragment g = todo.back();
      todo.pop_back();
      int k = 0;  // the longest side, from corner k
      double longest = 0;
      for (int i = 0; i < 3; ++i) {
        const double l = norm(g.at[(i + 1) % 3] - g.at[i]);
        if (l > longest) longest = l, k = i;
      }
      if (longest <= kFragmentMm) {
        out.push_back(g);
        continue;
      }
      // Halved across side k: both halves keep that side's border, and the new side has none.
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      const Vec2 m = 0.5 * (g.at[k] + g.at[k1]);
      const double md = 0.5 * (g.depth[k] + g.depth[k1]);
      const bool side = g.borders >> k & 1;
      Fragment a = g, b = g;
      a.at = {g.at[k], m, g.at[k2]};
      a.depth = {g.depth[k], md, g.depth[k2]};
      a.borders = static_cast<std::uint8_t>((side ? 1 : 0) | ((g.borders >> k2 & 1) << 2));
      b.at = {m, g.at[k1], g.at[k2]};
      b.depth = {md, g.depth[k1], g.depth[k2]};
      b.borders = static_cast<std::uint8_t>((side ? 1 : 0) | ((g.borders >> k1 & 1) << 1));
      todo.push_back(a);
      todo.push_back(b);
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const Fragment& a, const Fragment& b) {
    if (a.front != b.front) return !a.front;
    return a.depth[0] + a.depth[1] + a.depth[2] < b.depth[0] + b.depth[1] + b.depth[2];
  });
  return out;
}

void trace(cairo_t* cr, const Fragment& g) {
  cairo_move_to(cr, g.at[0].x, g.at[0].y);
  cairo_line_to(cr, g.at[1].x, g.at[1].y);
  cairo_line_to(cr, g.at[2].x, g.at[2].y);
  cairo_close_path(cr);
}

/// The shaded image at `dpi` of the box [lo, hi]: each face its piece's colour (or grey), lit from
/// the viewer's upper left, darker where its back shows (inside an open model); the borders of
/// pieces dark.
SurfacePtr shade(const Mesh& mesh, std::span<const int> piece, const std::vector<Fragment>& order,
                 Vec3 toward, Vec3 up, Vec2 lo, Vec2 hi, double dpi, bool colour) {
  // Painted kSupersample times finer without smoothing, then scaled down: fragments that meet
  // leave no seam (smoothed, each would let the paper show through half a pixel along its sides).
  const double px = dpi / 25.4;
  const int w = std::max(1, static_cast<int>(std::ceil((hi.x - lo.x) * px)));
  const int h = std::max(1, static_cast<int>(std::ceil((hi.y - lo.y) * px)));
  SurfacePtr fine(
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, kSupersample * w, kSupersample * h),
      cairo_surface_destroy);
  cairo_t* cr = cairo_create(fine.get());
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  cairo_scale(cr, kSupersample * px, kSupersample * px);
  cairo_translate(cr, -lo.x, -lo.y);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  const Vec3 view = unit(toward);
  const Vec3 light = unit(view + 0.6 * unit(up) - 0.4 * unit(cross(up, view)));
  std::vector<double> lit(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Vec3 n = unit(face_normal(mesh, static_cast<int>(f)));
    lit[f] = dot(n, view) >= 0 ? 0.62 + 0.38 * std::max(0.0, dot(n, light)) : 0.45;
  }
  for (const Fragment& g : order) {
    const double l = lit[g.face];
    const auto rgb = colour ? piece_rgb(piece[g.face]) : std::array<double, 3>{0.93, 0.93, 0.93};
    cairo_set_source_rgb(cr, l * rgb[0], l * rgb[1], l * rgb[2]);
    trace(cr, g);
    cairo_fill(cr);
    if (g.borders == 0) continue;
    cairo_set_source_rgb(cr, 0.12, 0.12, 0.12);
    cairo_set_line_width(cr, 0.3);
    for (int k = 0; k < 3; ++k)
      if (g.borders >> k & 1) {
        cairo_move_to(cr, g.at[k].x, g.at[k].y);
        cairo_line_to(cr, g.at[(k + 1) % 3].x, g.at[(k + 1) % 3].y);
      }
    cairo_stroke(cr);
  }
  cairo_destroy(cr);
  cairo_surface_flush(fine.get());
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h), cairo_surface_destroy);
  cr = cairo_create(surface.get());
  cairo_scale(cr, 1.0 / kSupersample, 1.0 / kSupersample);
  cairo_set_source_surface(cr, fine.get(), 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);
  cairo_paint(cr);
  cairo_destroy(cr);
  cairo_surface_flush(surface.get());
  return surface;
}

using print_detail::PageBox;

/// Which piece shows at each pixel (kItemsPerMm to the millimetre; -1: none), painted as
/// shade() paints, without smoothing.
struct Items {
  int width = 0, height = 0;
  std::vector<int> piece;
  int at(int x, int y) const { return piece[static_cast<std::size_t>(y) * width + x]; }
  /// The share of the pixels of `box` (page mm; the image's corner at `lo`) that show `p`
  /// (-1: the paper, off the model); 0 for a box outside the image.
  double share_of(const PageBox& box, Vec2 lo, int p) const {
    const int x0 = std::max(0, static_cast<int>((box.x0 - lo.x) * kItemsPerMm));
    const int x1 = std::min(width, static_cast<int>(std::ceil((box.x1 - lo.x) * kItemsPerMm)));
    const int y0 = std::max(0, static_cast<int>((box.y0 - lo.y) * kItemsPerMm));
    const int y1 = std::min(height, static_cast<int>(std::ceil((box.y1 - lo.y) * kItemsPerMm)));
    std::size_t on = 0, all = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x, ++all) on += at(x, y) == p;
    return all == 0 ? 0 : static_cast<double>(on) / static_cast<double>(all);
  }
  /// How far the segment from a to b (page mm) runs over pieces other than `p`, mm.
  double across(Vec2 a, Vec2 b, Vec2 lo, int p) const {
    const double length = norm(b - a);
    const int steps = std::max(1, static_cast<int>(std::ceil(length * kItemsPerMm)));
    int over = 0;
    for (int k = 0; k <= steps; ++k) {
      const Vec2 s = a + (static_cast<double>(k) / steps) * (b - a);
      const int x = static_cast<int>((s.x - lo.x) * kItemsPerMm);
      const int y = static_cast<int>((s.y - lo.y) * kItemsPerMm);
      if (x < 0 || y < 0 || x >= width || y >= height) continue;
      const int q = at(x, y);
      over += q >= 0 && q != p;
    }
    return length * over / (steps + 1);
  }
};

Items items(std::span<const int> piece, const std::vector<Fragment>& order, Vec2 lo, Vec2 hi) {
  Items out;
  out.width = std::max(1, static_cast<int>(std::ceil((hi.x - lo.x) * kItemsPerMm)));
  out.height = std::max(1, static_cast<int>(std::ceil((hi.y - lo.y) * kItemsPerMm)));
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, out.width, out.height),
                     cairo_surface_destroy);
  cairo_t* cr = cairo_create(surface.get());
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_paint(cr);
  cairo_scale(cr, kItemsPerMm, kItemsPerMm);
  cairo_translate(cr, -lo.x, -lo.y);
  for (const Fragment& g : order) {
    // Piece p as the colour p + 1 (0: no piece), 24 bits.
    const int id = piece[g.face] + 1;
    cairo_set_source_rgb(cr, (id >> 16 & 255) / 255.0, (id >> 8 & 255) / 255.0, (id & 255) / 255.0);
    trace(cr, g);
    cairo_fill(cr);
  }
  cairo_destroy(cr);
  cairo_surface_flush(surface.get());
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  out.piece.resize(static_cast<std::size_t>(out.width) * out.height);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      std::uint32_t v = 0;
      std::memcpy(&v, data + static_cast<std::ptrdiff_t>(y) * stride + 4 * x, 4);
      out.piece[static_cast<std::size_t>(y) * out.width + x] = static_cast<int>(v & 0xffffff) - 1;
    }
  return out;
}

/// Each pixel's distance (in pixels, 3-4 chamfer / 3) to the nearest pixel of another piece or
/// of none, or to the image's side.
std::vector<double> inner_distance(const Items& it) {
  const int w = it.width, h = it.height;
  constexpr int kFar = 1 << 28;
  std::vector<int> d(static_cast<std::size_t>(w) * h, kFar);
  const auto idx = [w](int x, int y) { return static_cast<std::size_t>(y) * w + x; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int p = it.at(x, y);
      if (p < 0 || x == 0 || y == 0 || x == w - 1 || y == h - 1 || it.at(x - 1, y) != p ||
          it.at(x + 1, y) != p || it.at(x, y - 1) != p || it.at(x, y + 1) != p)
        d[idx(x, y)] = p < 0 ? 0 : 3;
    }
  const auto relax = [&](int x, int y, int nx, int ny, int cost) {
    if (nx < 0 || ny < 0 || nx >= w || ny >= h) return;
    d[idx(x, y)] = std::min(d[idx(x, y)], d[idx(nx, ny)] + cost);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      relax(x, y, x - 1, y, 3), relax(x, y, x, y - 1, 3);
      relax(x, y, x - 1, y - 1, 4), relax(x, y, x + 1, y - 1, 4);
    }
  for (int y = h - 1; y >= 0; --y)
    for (int x = w - 1; x >= 0; --x) {
      relax(x, y, x + 1, y, 3), relax(x, y, x, y + 1, 3);
      relax(x, y, x + 1, y + 1, 4), relax(x, y, x - 1, y + 1, 4);
    }
  std::vector<double> out(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) out[i] = d[i] / 3.0;
  return out;
}

}  // namespace

ViewAxes view_axes(MeshFormat format) {
  if (format == MeshFormat::Stl) return {{0, 0, 1}, {0, -1, 0}};
  return {};
}

ModelView draw_model_view(const Mesh& mesh, std::span<const int> piece, Vec3 toward, Vec3 up,
                          Vec2 lo, Vec2 hi, double dpi, bool colour) {
  ModelView view;
  if (mesh.faces.empty() || piece.size() != mesh.faces.size() || !(hi.x > lo.x && hi.y > lo.y))
    return view;
  const Projection p = project(mesh, toward, up, lo, hi);
  const std::vector<Fragment> order = paint_order(mesh, piece, p, toward);
  view.image = {lo, hi.x - lo.x, hi.y - lo.y,
                shade(mesh, piece, order, toward, up, lo, hi, dpi, colour)};

  // Each piece's number on the pixels where it shows, at its pixels farthest inside first, at
  // the largest size whose box shows its piece on kOnPiece of its pixels and meets no number.
  const Items it = items(piece, order, lo, hi);
  const std::vector<double> inside = inner_distance(it);
  int pieces = 0;
  for (const int q : piece) pieces = std::max(pieces, q + 1);
  std::vector<std::vector<std::size_t>> pixels(static_cast<std::size_t>(pieces));
  // Each piece's pixels, and the middle of them: where a line to a piece that shows too little
  // for its number ends is the pixel farthest inside it, the nearest the middle of those.
  std::vector<std::size_t> shown(static_cast<std::size_t>(pieces), 0);
  std::vector<Vec2> middle(static_cast<std::size_t>(pieces));
  for (std::size_t i = 0; i < it.piece.size(); ++i) {
    const int q = it.piece[i];
    if (q < 0 || q >= pieces) continue;
    ++shown[q];
    middle[q] =
        middle[q] + Vec2{static_cast<double>(i % it.width), static_cast<double>(i / it.width)};
    if (inside[i] >= 2) pixels[q].push_back(i);
  }
  std::vector<std::size_t> deepest(static_cast<std::size_t>(pieces), 0);
  std::vector<double> off(static_cast<std::size_t>(pieces), 0);
  for (std::size_t i = 0; i < it.piece.size(); ++i) {
    const int q = it.piece[i];
    if (q < 0 || q >= pieces) continue;
    const double d =
        norm(Vec2{static_cast<double>(i % it.width), static_cast<double>(i / it.width)} -
             (1.0 / static_cast<double>(shown[q])) * middle[q]);
    const double best = inside[deepest[q]];
    if (it.piece[deepest[q]] != q || inside[i] > best || (inside[i] == best && d < off[q]))
      deepest[q] = i, off[q] = d;
  }
  std::vector<PageBox> taken;
  std::vector<std::array<Vec2, 2>> lines;  // from the numbers beside the model
  const auto centre_of = [&](std::size_t i) {
    return Vec2{lo.x + (static_cast<double>(i % it.width) + 0.5) / kItemsPerMm,
                lo.y + (static_cast<double>(i / it.width) + 0.5) / kItemsPerMm};
  };
  const auto half_of = [](const std::string& name, double size) {
    return Vec2{0.5 * text_width(name, size) + 0.2, 0.5 * size + 0.2};
  };
  const auto box_of = [&](Vec2 c, const std::string& name, double size) {
    const Vec2 half = half_of(name, size);
    return PageBox{c.x - half.x, c.y - half.y, c.x + half.x, c.y + half.y};
  };
  const PageBox image{lo.x, lo.y, hi.x, hi.y};
  const auto free = [&](const PageBox& box) {
    return image.holds(box) &&
           std::none_of(taken.begin(), taken.end(),
                        [&](const PageBox& o) { return box.overlaps(o); }) &&
           std::none_of(lines.begin(), lines.end(),
                        [&](const std::array<Vec2, 2>& l) { return box.crosses(l[0], l[1]); });
  };
  constexpr std::size_t kTries = 40;  // pixels tried per piece and size, farthest inside first
  std::vector<char> numbered(static_cast<std::size_t>(pieces), 0);
  for (int q = 0; q < pieces; ++q) {
    std::vector<std::size_t>& own = pixels[q];
    if (own.empty()) continue;
    const std::size_t tries = std::min(kTries, own.size());
    std::partial_sort(own.begin(), own.begin() + static_cast<std::ptrdiff_t>(tries), own.end(),
                      [&](std::size_t a, std::size_t b) { return inside[a] > inside[b]; });
    const std::string name = piece_name(q);
    for (const double size : kViewNumberMm) {
      for (std::size_t t = 0; t < tries && !numbered[q]; ++t) {
        const Vec2 c = centre_of(own[t]);
        const PageBox box = box_of(c, name, size);
        if (!free(box) || it.share_of(box, lo, q) < kOnPiece) continue;
        taken.push_back(box);
        view.numbers.push_back({q, c, size, c, c});
        numbered[q] = 1;
      }
      if (numbered[q]) break;
    }
  }
  // A piece that shows too little for its number on it gets it beside the model, on paper off
  // the model nearest where the piece shows most, with a line to there, clear of the numbers (and
  // no number on the lines before it).
  const double size = kViewNumberMm[1];
  for (int q = 0; q < pieces; ++q) {
    if (numbered[q] || shown[q] < kLeaderPixels) continue;
    const Vec2 to = centre_of(deepest[q]);
    // The line starts at the point of the number's box nearest the piece.
    const auto from_of = [&](const PageBox& box) {
      return Vec2{std::clamp(to.x, box.x0, box.x1), std::clamp(to.y, box.y0, box.y1)};
    };
    // The place: off the model (the box all paper), its line clear of the numbers and over
    // other pieces for at most kLeaderAcrossMm.
    const auto beside = [&](const PageBox& box) {
      if (!free(box) || it.share_of(box, lo, -1) < 1) return false;
      const Vec2 from = from_of(box);
      return std::none_of(taken.begin(), taken.end(),
                          [&](const PageBox& o) { return o.crosses(from, to); }) &&
             it.across(from, to, lo, q) <= kLeaderAcrossMm;
    };
    const std::string name = piece_name(q);
    const std::optional<Vec2> c =
        print_detail::ring_place(to, half_of(name, size), image, kLeaderRings, beside);
    if (!c) continue;
    const PageBox box = box_of(*c, name, size);
    const Vec2 from = from_of(box);
    taken.push_back(box);
    lines.push_back({from, to});
    view.numbers.push_back({q, *c, size, from, to});
    numbered[q] = 1;
  }
  return view;
}

}  // namespace papernet
