#include "print/pages.h"

#include <cairo.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <numbers>

#include "core/ascii.h"
#include "core/errors.h"
#include "print/overview.h"

namespace papernet {

namespace {

/// Parses a leading number; returns the rest of the string in `rest`.
bool leading_number(std::string_view s, double& value, std::string_view& rest) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || end == s.data()) return false;
  rest = s.substr(static_cast<std::size_t>(end - s.data()));
  return std::isfinite(value);
}

/// The shortest text that reads back as `v` ("297", "215.9").
std::string shortest(double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : std::to_string(v);
}

}  // namespace

const std::vector<Paper>& named_papers() {
  static const std::vector<Paper> papers = {{"A4", 210, 297},        {"A3", 297, 420},
                                            {"A5", 148, 210},        {"Letter", 215.9, 279.4},
                                            {"Legal", 215.9, 355.6}, {"Tabloid", 279.4, 431.8}};
  return papers;
}

std::string paper_names() {
  std::string out;
  for (const Paper& p : named_papers()) out += p.name + ", ";
  return out + "WxHmm";
}

Paper parse_paper(std::string_view text) {
  const std::string t = ascii_lower(text);
  for (const Paper& p : named_papers())
    if (t == ascii_lower(p.name)) return p;
  double w = 0, h = 0;
  std::string_view rest;
  const std::string_view s = t;
  if (leading_number(s, w, rest) && rest.starts_with("x") &&
      leading_number(rest.substr(1), h, rest) && (rest.empty() || rest == "mm") && w > 0 && h > 0 &&
      w < 1e5 && h < 1e5)
    return {shortest(w) + "x" + shortest(h) + "mm", std::min(w, h), std::max(w, h)};
  throw InvalidOptionException(
      "invalid_option_value", "paper",
      "unknown paper '" + std::string(text) + "': use " + paper_names() + " (e.g. 300x200mm)");
}

double parse_length_mm(std::string_view text) {
  const std::string t = ascii_lower(text);
  double v = 0;
  std::string_view unit;
  if (leading_number(t, v, unit) && v > 0) {
    if (unit.empty() || unit == "mm") return v;
    if (unit == "cm") return 10 * v;
    if (unit == "in") return 25.4 * v;
    if (unit == "pt") return 25.4 / 72 * v;
  }
  throw InvalidOptionException("invalid_option_value", "",
                               "bad length '" + std::string(text) +
                                   "': use a positive number with mm, cm, in or pt (e.g. 200mm)");
}

void PageOptions::validate() const {
  const auto fail = [](const char* option, const std::string& message) {
    throw InvalidOptionException("option_out_of_range", option, message);
  };
  if (!std::isfinite(margin_mm) || margin_mm < 0) fail("margin_mm", "margin must be >= 0 mm");
  if (!std::isfinite(overlap_mm) || overlap_mm < 0) fail("overlap_mm", "overlap must be >= 0 mm");
  const double w = paper.width - 2 * margin_mm, h = paper.height - 2 * margin_mm;
  const auto mm = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g mm", v);
    return std::string(text);
  };
  if (w <= 0 || h <= 0)
    fail("margin_mm", "margins of " + mm(margin_mm) + " leave no printable area on " + paper.name +
                          " paper (" + mm(paper.width) + " x " + mm(paper.height) + ")");
  // Named with the figures: a person who set only the paper learns which of the three to change.
  if (overlap_mm >= 0.5 * std::min(w, h))
    fail("overlap_mm", "the overlap of tiled pages (" + mm(overlap_mm) +
                           ") must be less than half the printable area's narrower side: " +
                           paper.name + " paper within margins of " + mm(margin_mm) + " prints " +
                           mm(std::min(w, h)) + " across");
}

namespace {

std::array<Vec2, 4> window_of(const Page& page) {
  return {page.lo, Vec2{page.hi.x, page.lo.y}, page.hi, Vec2{page.lo.x, page.hi.y}};
}

/// True when a face or tab of the layout reaches into the page's window (a sparse net tiled
/// onto a grid can leave pages empty: those are not printed).
bool shows_net(const PrintLayout& layout, const Page& page) {
  const auto window = window_of(page);
  for (const auto& f : layout.faces)
    if (convex_overlap(f, window, 0)) return true;
  for (const Tab& t : layout.tabs)
    if (convex_overlap(t.corners, window, 0)) return true;
  return false;
}

bool contains(const Page& page, const GlueStrip& strip) {
  for (Vec2 p : strip.corners)
    if (p.x < page.lo.x || p.x > page.hi.x || p.y < page.lo.y || p.y > page.hi.y) return false;
  return true;
}

/// Which tiles are printed: those showing part of the net, and for each glue strip not wholly
/// on one of those, a tile that holds it wholly (else every tile it reaches into).
std::vector<Page> printed_tiles(const PrintLayout& layout, const std::vector<Page>& tiles) {
  std::vector<char> printed(tiles.size());
  for (std::size_t t = 0; t < tiles.size(); ++t) printed[t] = shows_net(layout, tiles[t]);
  for (const GlueStrip& strip : layout.strips) {
    bool held = false;
    for (std::size_t t = 0; t < tiles.size() && !held; ++t)
      held = printed[t] && contains(tiles[t], strip);
    for (std::size_t t = 0; t < tiles.size() && !held; ++t)
      if (contains(tiles[t], strip)) printed[t] = held = true;
    for (std::size_t t = 0; t < tiles.size() && !held; ++t)
      if (convex_overlap(strip.corners, window_of(tiles[t]), 0)) printed[t] = 1;
  }
  std::vector<Page> out;
  for (std::size_t t = 0; t < tiles.size(); ++t)
    if (printed[t]) out.push_back(tiles[t]);
  return out;
}

}  // namespace

void turn_quarter(PrintLayout& layout) {
  const double h = layout.size.y;
  auto turn = [h](Vec2& p) { p = {h - p.y, p.x}; };
  for (auto& f : layout.faces)
    for (Vec2& p : f) turn(p);
  for (Tab& t : layout.tabs)
    for (Vec2& p : t.corners) turn(p);
  for (GlueStrip& t : layout.strips)
    for (Vec2& p : t.corners) turn(p);
  for (auto* list : {&layout.cut, &layout.mountain, &layout.valley, &layout.leaders})
    for (Segment& s : *list) turn(s.a), turn(s.b);
  for (Label& l : layout.labels) {
    turn(l.at);
    // Keep labels reading upright: half a turn more where a quarter turn put them upside down.
    l.angle += std::cos(l.angle + std::numbers::pi / 2) < -1e-9 ? 1.5 * std::numbers::pi
                                                                : std::numbers::pi / 2;
  }
  // Piece numbers stay level (print/internal/piece_labels.h).
  for (Label& l : layout.piece_labels) turn(l.at);
  layout.size = {layout.size.y, layout.size.x};
}

namespace {

/// The tiles of `layout` on pages of `pw` x `ph` that show something.
/// Moves glue strips that none of `net_windows` holds wholly into free space inside one of them
/// where there is room.
void pull_strips_onto(PrintLayout& layout, const std::vector<std::pair<Vec2, Vec2>>& net_windows) {
  std::vector<int> stray;
  for (int i = 0; i < static_cast<int>(layout.strips.size()); ++i) {
    bool held = false;
    for (const auto& [lo, hi] : net_windows)
      held = held || contains({0, 0, lo, hi}, layout.strips[i]);
    if (!held) stray.push_back(i);
  }
  if (stray.empty() || net_windows.empty()) return;
  std::vector<StripRequest> requests;
  for (int i : stray) {
    const GlueStrip& g = layout.strips[i];
    Vec2 near = 0.25 * (g.corners[0] + g.corners[1] + g.corners[2] + g.corners[3]);
    if (g.edge >= 0 && g.edge < static_cast<int>(layout.edges.size())) {
      const EdgeSide a = layout.edges[g.edge].a;
      near = 0.5 * (layout.faces[a.face][a.k] + layout.faces[a.face][(a.k + 1) % 3]);
    }
    requests.push_back(
        {g.edge, norm(g.corners[1] - g.corners[0]), norm(g.corners[3] - g.corners[0]), near});
  }
  StripOptions options;
  options.within = net_windows;
  // Every strip where it is now is an obstacle: a strip that finds no better place stays put.
  const std::vector<GlueStrip> moved =
      place_strips(layout.faces, layout.tabs, requests, layout.strips, options);
  for (const GlueStrip& m : moved) {
    bool held = false;
    for (const auto& [lo, hi] : net_windows) held = held || contains({0, 0, lo, hi}, m);
    if (!held) continue;
    for (int i : stray)
      if (layout.strips[i].edge == m.edge) {
        layout.strips[i].corners = m.corners;
        break;
      }
  }
}

PageLayout tile(PrintLayout& layout, double pw, double ph, const PageOptions& options, bool pull) {
  const double m = options.margin_mm, ov = options.overlap_mm;
  const double w = pw - 2 * m, h = ph - 2 * m;
  auto tiles = [ov](double content, double room) {
    return content <= room ? 1 : static_cast<int>(std::ceil((content - ov) / (room - ov)));
  };
  PageLayout out;
  out.width = pw, out.height = ph, out.margin = m, out.overlap = ov;
  out.rows = tiles(layout.size.y, h), out.cols = tiles(layout.size.x, w);
  // The tiles together cover (cols * (w - ov) + ov) x (rows * (h - ov) + ov); centre the net.
  const double tw = out.cols * (w - ov) + ov, th = out.rows * (h - ov) + ov;
  const Vec2 off{0.5 * (tw - layout.size.x), 0.5 * (th - layout.size.y)};
  std::vector<Page> grid;
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) {
      const double x0 = c * (w - ov) - off.x, y1 = th - r * (h - ov) - off.y;
      grid.push_back({r, c, {x0, y1 - h}, {x0 + w, y1}});
    }
  if (pull) {
    // Strips that no tile showing the net holds wholly would need a page of their own or print
    // split: move them onto the net's tiles where there is room, else wholly onto any tile.
    std::vector<std::pair<Vec2, Vec2>> net_windows, all_windows;
    for (const Page& p : grid) {
      all_windows.emplace_back(p.lo, p.hi);
      if (shows_net(layout, p)) net_windows.push_back(all_windows.back());
    }
    pull_strips_onto(layout, net_windows);
    pull_strips_onto(layout, all_windows);
  }
  out.pages = printed_tiles(layout, grid);
  return out;
}

}  // namespace

std::string_view page_layout_name(PageLayoutMode mode) {
  return mode == PageLayoutMode::Fit ? "fit" : "tile";
}

PageLayout paginate(PrintLayout& layout, const PageOptions& options) {
  options.validate();
  // Candidates: portrait pages with the net's long side along the page's long side, portrait
  // with it across, then the same on landscape pages. Fewest printed pages wins; ties keep the
  // earlier.
  PrintLayout turned = layout;
  turn_quarter(turned);
  const bool wide = layout.size.x > layout.size.y;
  PageLayout best;
  double best_pw = 0, best_ph = 0;
  for (int c = 0; c < 4; ++c) {
    const bool landscape = c >= 2, turn = (c % 2 == 1) != (wide != landscape);
    const double pw = landscape ? options.paper.height : options.paper.width;
    const double ph = landscape ? options.paper.width : options.paper.height;
    PageLayout candidate = tile(turn ? turned : layout, pw, ph, options, false);
    candidate.quarter_turn = turn;
    if (c == 0 || candidate.pages.size() < best.pages.size())
      best = std::move(candidate), best_pw = pw, best_ph = ph;
  }
  if (best.quarter_turn) layout = std::move(turned);
  // The choice made, glue strips that would print alone or split move onto the net's pages.
  if (!layout.strips.empty()) {
    const bool turn = best.quarter_turn;
    best = tile(layout, best_pw, best_ph, options, true);
    best.quarter_turn = turn;
  }
  return best;
}

namespace {

bool box_meets(const std::vector<Vec2>& pts, Vec2 lo, Vec2 hi) {
  Vec2 a = pts[0], b = pts[0];
  for (Vec2 p : pts)
    a = {std::min(a.x, p.x), std::min(a.y, p.y)}, b = {std::max(b.x, p.x), std::max(b.y, p.y)};
  return a.x <= hi.x && b.x >= lo.x && a.y <= hi.y && b.y >= lo.y;
}

// The colour of the faces where no image covers them (print/pdf.cpp, print/svg.cpp), and the
// relative luminance (linear light) under which white text reads better than the labels' dark
// grey (#333333): the two have the same contrast ratio there.
constexpr unsigned kFaceFill = 0xf3f6fb;
constexpr double kDarkLuminance = 0.245;

double linear(double srgb) {
  return srgb <= 0.04045 ? srgb / 12.92 : std::pow((srgb + 0.055) / 1.055, 2.4);
}

/// The relative luminance of the page at `q` (mm): the topmost image that covers it over the
/// faces' fill.
double luminance_at(const std::vector<PageImage>& images, Vec2 q) {
  double rgb[3] = {((kFaceFill >> 16) & 0xff) / 255.0, ((kFaceFill >> 8) & 0xff) / 255.0,
                   (kFaceFill & 0xff) / 255.0};
  for (auto it = images.rbegin(); it != images.rend(); ++it) {
    cairo_surface_t* surface = it->surface.get();
    const int w = cairo_image_surface_get_width(surface),
              h = cairo_image_surface_get_height(surface);
    if (!(it->width > 0 && it->height > 0) || w <= 0 || h <= 0) continue;
    const double fx = (q.x - it->at.x) / it->width * w, fy = (q.y - it->at.y) / it->height * h;
    if (!(fx >= 0 && fy >= 0 && fx < w && fy < h)) continue;
    const unsigned char* row =
        cairo_image_surface_get_data(surface) +
        static_cast<std::ptrdiff_t>(fy) * cairo_image_surface_get_stride(surface);
    std::uint32_t argb;
    std::memcpy(&argb, row + 4 * static_cast<std::ptrdiff_t>(fx), 4);
    const double a = (argb >> 24) / 255.0;
    if (a <= 0) continue;
    // Premultiplied ARGB32 over the fill.
    for (int c = 0; c < 3; ++c) rgb[c] = ((argb >> (16 - 8 * c)) & 0xff) / 255.0 + (1 - a) * rgb[c];
    break;
  }
  return 0.2126 * linear(rgb[0]) + 0.7152 * linear(rgb[1]) + 0.0722 * linear(rgb[2]);
}

/// Labels over a dark colour (a black tyre, a dark texture) are drawn white: the mean luminance
/// of 15 points over the text's box decides. So are leader lines, by 5 points along them.
void light_labels_over_dark(PageDrawing& d) {
  if (d.images.empty()) return;
  for (const PageImage& image : d.images) cairo_surface_flush(image.surface.get());
  for (Shape& s : d.shapes) {
    if (s.layer == Layer::Leaders && s.points.size() == 2) {  // by five points along the line
      double sum = 0;
      for (const double t : {0.1, 0.3, 0.5, 0.7, 0.9})
        sum += luminance_at(d.images, s.points[0] + t * (s.points[1] - s.points[0]));
      s.light = sum / 5 < kDarkLuminance;
      continue;
    }
    if (s.layer != Layer::Labels || s.text.empty() || s.points.empty()) continue;
    const double turn = s.angle_deg * std::numbers::pi / 180;
    const Vec2 along{std::cos(turn), std::sin(turn)}, across{-along.y, along.x};
    const double half_width = 0.5 * text_width(s.text, s.size), half_height = 0.3 * s.size;
    double sum = 0;
    int n = 0;
    for (const double u : {-0.8, -0.4, 0.0, 0.4, 0.8})
      for (const double v : {-1.0, 0.0, 1.0}) {
        sum += luminance_at(d.images,
                            s.points[0] + (u * half_width) * along + (v * half_height) * across);
        ++n;
      }
    s.light = sum / n < kDarkLuminance;
  }
}

/// Adds the layout's shapes inside window [lo, hi] (layout coordinates), mapped to the page with
/// the window's top-left corner at `at`.
void add_layout(const PrintLayout& layout, Vec2 lo, Vec2 hi, Vec2 at, PageDrawing& d) {
  auto map = [&](Vec2 p) { return Vec2{at.x + (p.x - lo.x), at.y + (hi.y - p.y)}; };
  auto add = [&](Layer layer, std::vector<Vec2> pts, bool closed) {
    if (!box_meets(pts, lo, hi)) return;
    for (Vec2& p : pts) p = map(p);
    d.shapes.push_back({layer, std::move(pts), closed, {}, 0, 0});
  };
  for (const auto& f : layout.faces) add(Layer::Faces, {f[0], f[1], f[2]}, true);
  for (const Tab& t : layout.tabs) add(Layer::Tabs, {t.corners.begin(), t.corners.end()}, true);
  for (const GlueStrip& t : layout.strips) {
    if (!box_meets({t.corners.begin(), t.corners.end()}, lo, hi)) continue;
    add(Layer::Strips, {t.corners.begin(), t.corners.end()}, true);
    const StripMarks m = strip_marks(t);
    add(Layer::Strips, {m.seam0, m.seam1}, false);
    if (t.text.empty() || !(t.text_size > 0)) continue;
    // The label on each half, upright on the page where it can be.
    double angle = m.angle;
    if (std::cos(angle) < -1e-9) angle += std::numbers::pi;
    for (Vec2 p : m.label_at)
      d.shapes.push_back(
          {Layer::Strips, {map(p)}, false, t.text, t.text_size, -angle * 180 / std::numbers::pi});
  }
  for (const Segment& s : layout.cut) add(Layer::Cut, {s.a, s.b}, false);
  for (const Segment& s : layout.mountain) add(Layer::Mountain, {s.a, s.b}, false);
  for (const Segment& s : layout.valley) add(Layer::Valley, {s.a, s.b}, false);
  for (const Segment& s : layout.leaders) add(Layer::Leaders, {s.a, s.b}, false);
  for (const Label& l : layout.piece_labels) {
    if (l.text.empty()) continue;
    const auto box = label_box(l);
    if (!box_meets({box.begin(), box.end()}, lo, hi)) continue;
    d.shapes.push_back(
        {Layer::Labels, {map(l.at)}, false, l.text, l.size, -l.angle * 180 / std::numbers::pi});
  }
  for (const Label& l : layout.labels) {
    const auto box = label_box(l);
    if (!box_meets({box.begin(), box.end()}, lo, hi)) continue;
    d.shapes.push_back(
        {Layer::Labels, {map(l.at)}, false, l.text, l.size, -l.angle * 180 / std::numbers::pi});
  }
}

/// The key to the lines, centred in the top margin: a sample of each line beside its name
/// ("cut", "mountain fold", "valley fold"), the samples in their layers' styles. Its text is the
/// page line's size, smaller where the page is narrow, and it keeps clear of the tiles' overlap
/// ticks; left out where the margin or the page is too small for it.
void add_key(PageDrawing& d, const PageLayout& pages) {
  struct Entry {
    Layer layer;
    const char* name;
  };
  static constexpr Entry kEntries[] = {
      {Layer::Cut, "cut"}, {Layer::Mountain, "mountain fold"}, {Layer::Valley, "valley fold"}};
  const double m = pages.margin;
  if (m < 5) return;  // no room above the printable area
  const double room = pages.width - 2 * (m + pages.overlap);
  // A sample three text heights long, never under 8 mm (the valley's dash-dot is 3.8 mm a
  // period); 0.6 of a text height before its name, 2.4 between entries.
  auto sample = [](double size) { return std::max(3 * size, 8.0); };
  auto width = [&](double size) {
    double w = 2 * 2.4 * size;
    for (const Entry& e : kEntries) w += sample(size) + 0.6 * size + text_width(e.name, size);
    return w;
  };
  double size = std::clamp(0.4 * m, 1.5, 3.5);
  for (int i = 0; i < 4 && width(size) > room; ++i) size = std::max(1.5, size * room / width(size));
  const double total = width(size);
  if (total > room) return;
  double x = 0.5 * (pages.width - total);
  const double y = 0.5 * m;
  for (const Entry& e : kEntries) {
    Shape line{e.layer, {{x, y}, {x + sample(size), y}}, false, {}, 0, 0};
    line.key = true;
    d.shapes.push_back(std::move(line));
    x += sample(size) + 0.6 * size;
    const double w = text_width(e.name, size);
    d.shapes.push_back({Layer::Marks, {{x + 0.5 * w, y}}, false, e.name, size, 0});
    x += w + 2.4 * size;
  }
}

}  // namespace

PageDrawing draw_page(const PrintLayout& layout, const PageLayout& pages, int index,
                      const PrintColour* colour) {
  const Page& page = pages.pages.at(static_cast<std::size_t>(index));
  const double m = pages.margin;
  PageDrawing d{pages.width, pages.height, {m, m}, {pages.width - m, pages.height - m}, {}, {}, {}};
  if (page.overview && pages.overview)
    d = draw_overview(layout, pages, index);
  else
    add_layout(layout, page.lo, page.hi, {m, m}, d);
  if (colour && !page.overview) {
    d.images = colour_images(layout, *colour, page.lo, page.hi, {m, m}, d.clip_lo, d.clip_hi);
    light_labels_over_dark(d);
  }
  auto mark = [&](Vec2 a, Vec2 b) { d.shapes.push_back({Layer::Marks, {a, b}, false, {}, 0, 0}); };
  const double ov = pages.overlap, x1 = pages.width - m, y1 = pages.height - m;
  // Overlap marks: where the neighbouring tile's window begins, with ticks in the margin so the
  // sheets can be aligned after cutting the margins.
  if (!pages.fitted && page.col + 1 < pages.cols)
    mark({x1 - ov, m - 0.8 * m}, {x1 - ov, y1 + 0.8 * m});
  if (!pages.fitted && page.col > 0) mark({m + ov, m - 0.8 * m}, {m + ov, y1 + 0.8 * m});
  if (!pages.fitted && page.row + 1 < pages.rows)
    mark({m - 0.8 * m, y1 - ov}, {x1 + 0.8 * m, y1 - ov});
  if (!pages.fitted && page.row > 0) mark({m - 0.8 * m, m + ov}, {x1 + 0.8 * m, m + ov});
  std::string name = (pages.title.empty() ? "" : pages.title + " \u00b7 ") + "page " +
                     std::to_string(index + 1) + " of " + std::to_string(pages.pages.size());
  if (page.overview) name += ": overview";
  if (!pages.fitted && pages.pages.size() > 1)
    name +=
        " (row " + std::to_string(page.row + 1) + ", column " + std::to_string(page.col + 1) + ")";
  // Smaller on paper too narrow for the line (text_width: a character of sans-serif is at most
  // about 0.6 of its size wide): 50 mm paper's "page 30 of 560 (row 3, column 8)" ran past both
  // edges.
  const double fs =
      std::min(std::clamp(0.4 * m, 1.5, 3.5), 0.9 * pages.width / text_width(name, 1));
  d.shapes.push_back(
      {Layer::Marks, {{0.5 * pages.width, pages.height - 0.5 * m}}, false, name, fs, 0});
  d.title = std::move(name);
  add_key(d, pages);
  return d;
}

PageDrawing draw_unpaged(const PrintLayout& layout, double margin_mm, const PrintColour* colour) {
  const double m = std::max(0.0, margin_mm);
  PageDrawing d{layout.size.x + 2 * m, layout.size.y + 2 * m, {0, 0}, {}, {}, {}, {}};
  d.clip_hi = {d.width, d.height};
  const Vec2 lo{-m, -m}, hi{layout.size.x + m, layout.size.y + m};
  add_layout(layout, lo, hi, {0, 0}, d);
  if (colour) {
    d.images = colour_images(layout, *colour, lo, hi, {0, 0}, d.clip_lo, d.clip_hi);
    light_labels_over_dark(d);
  }
  return d;
}

}  // namespace papernet
