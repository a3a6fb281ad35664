#include "print/nest.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include "core/errors.h"
#include "core/unfold/net_metrics.h"
#include "print/internal/nest_outlines.h"
#include "print/strips.h"

namespace papernet {
namespace {

// The nesting grid works in integer coordinates: micrometres (on a sheet up to kMostNestMm long).
constexpr double kUnitsPerMm = 1000;
// The longest sheet nested at nest_outlines' cells of 0.5 mm (the named papers all are, Tabloid's
// 432 mm the longest); a longer one is nested scaled down to this (nest_parts).
constexpr double kMostNestMm = 450;

/// `p` (mm) in units of which `units` make a millimetre.
print_detail::IntPoint to_int(Vec2 p, double units) {
  return {std::llround(p.x * units), std::llround(p.y * units)};
}

/// What is nested: the shapes of one piece (its faces and their tabs) or one glue strip, turned
/// by `turn` about the origin before it is nested.
struct Part {
  std::vector<std::vector<Vec2>> shapes;
  double turn = 0;
};

/// A turn (radians, counter-clockwise) that puts the points in a `room` box: of the turns that
/// lay one of their hull's edges along x or y and fit, the one with the smallest box; else of
/// the turns every quarter degree (a piece that fits the room at a turn along one of its own
/// hull's edges may fit with its tabs at none of theirs); none fitting, the minimum-area box's
/// with its long side along y.
double fitting_turn(const std::vector<Vec2>& points, Vec2 room) {
  const std::vector<Vec2> hull = convex_hull(points);
  double best = 0, best_area = std::numeric_limits<double>::infinity();
  const auto consider = [&](double turn) {
    Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    Vec2 hi = -1 * lo;
    for (Vec2 p : hull) {
      const Vec2 q = rotate(p, turn);
      lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)},
      hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
    }
    const Vec2 size = hi - lo;
    const double area = size.x * size.y;
    if (size.x <= room.x && size.y <= room.y && area < best_area) best = turn, best_area = area;
  };
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec2 d = hull[(i + 1) % hull.size()] - hull[i];
    for (const double quarter : {0.0, 0.5 * std::numbers::pi})
      consider(quarter - std::atan2(d.y, d.x));
  }
  for (int step = 0; step < 4 * 180 && !(best_area < std::numeric_limits<double>::infinity());
       ++step)
    consider(step * std::numbers::pi / (4 * 180));
  if (best_area < std::numeric_limits<double>::infinity()) return best;
  const OrientedBox box = min_area_box(points);
  return box.angle + (box.width() > box.height() ? 0.5 * std::numbers::pi : 0.0);
}

}  // namespace

namespace {

/// Nests parts onto sheets numbered from `first_sheet`: each part turned to fit, its outline
/// nested on a grid of cells (print/internal/nest_outlines.h). Returns each part's turn and shift
/// in layout coordinates (sheet k is the window at x = k * (w + kSheetGap)) and the sheets used.
constexpr double kSheetGap = 20;

struct Placement {
  std::vector<double> angle;
  std::vector<Vec2> shift;
  int sheets = 0;
};

Placement nest_parts(std::vector<Part>& parts, double w, double h, double spacing_mm,
                     int first_sheet, const std::string& paper) {
  // Each part keeps half the spacing of paper around it; its turn is chosen on its points with
  // room for that (and a few micrometres of rounding to spare).
  const double grow = 0.5 * spacing_mm;
  // A sheet longer than kMostNestMm is nested as one that long, every part scaled down with it:
  // its grid's cells grow with the sheet, so that a sheet of a plotter's size nests in about the
  // time A3 does rather than in the square of its size times longer.
  const double shrink = std::max(1.0, std::max(w, h) / kMostNestMm);
  const double units = kUnitsPerMm / shrink;  // nest_outlines' units per millimetre
  std::vector<print_detail::NestPart> turned;
  for (Part& part : parts) {
    std::vector<Vec2> points;
    for (const auto& shape : part.shapes) points.insert(points.end(), shape.begin(), shape.end());
    part.turn = fitting_turn(points, {w - 2 * grow - 0.01, h - 2 * grow - 0.01});
    print_detail::NestPart& polygons = turned.emplace_back();
    for (const auto& shape : part.shapes) {
      std::vector<print_detail::IntPoint>& polygon = polygons.emplace_back();
      for (Vec2 p : shape) polygon.push_back(to_int(rotate(p, part.turn), units));
    }
  }
  const std::vector<print_detail::NestedOutline> placed = print_detail::nest_outlines(
      turned, std::llround(grow * units), static_cast<std::int64_t>(std::floor(w * units)),
      static_cast<std::int64_t>(std::floor(h * units)));
  Placement out;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (placed[i].sheet < 0)
      throw InvalidOptionException(
          "face_too_large", "size_mm",
          "a piece does not fit the printable area of " + paper + " paper");
    out.sheets = std::max(out.sheets, placed[i].sheet + 1);
    out.angle.push_back(parts[i].turn + placed[i].angle);
    out.shift.push_back(
        Vec2{static_cast<double>(placed[i].dx) / units, static_cast<double>(placed[i].dy) / units} +
        Vec2{(first_sheet + placed[i].sheet) * (w + kSheetGap), 0});
  }
  return out;
}

bool inside(const GlueStrip& strip, Vec2 lo, Vec2 hi) {
  for (Vec2 p : strip.corners)
    if (p.x < lo.x || p.x > hi.x || p.y < lo.y || p.y > hi.y) return false;
  return true;
}

}  // namespace

PageLayout nest_pages(PrintLayout& layout, const std::vector<int>& piece,
                      const PageOptions& options, double spacing_mm) {
  options.validate();
  const double w = options.paper.width - 2 * options.margin_mm;
  const double h = options.paper.height - 2 * options.margin_mm;
  int pieces = 0;
  for (int p : piece) pieces = std::max(pieces, p + 1);

  // The pieces, each with its tabs, nested.
  std::vector<Part> parts(static_cast<std::size_t>(pieces));
  for (std::size_t f = 0; f < layout.faces.size(); ++f)
    parts[piece[f]].shapes.push_back({layout.faces[f].begin(), layout.faces[f].end()});
  for (const Tab& t : layout.tabs)
    parts[piece[t.side.face]].shapes.push_back({t.corners.begin(), t.corners.end()});
  const Placement placed = nest_parts(parts, w, h, spacing_mm, 0, options.paper.name);
  auto move = [&](std::size_t part, Vec2 p) {
    return rotate(p, placed.angle[part]) + placed.shift[part];
  };
  for (std::size_t f = 0; f < layout.faces.size(); ++f)
    for (Vec2& p : layout.faces[f]) p = move(piece[f], p);
  for (Tab& t : layout.tabs)
    for (Vec2& p : t.corners) p = move(piece[t.side.face], p);
  for (auto* list : {&layout.cut, &layout.mountain, &layout.valley, &layout.leaders})
    for (Segment& s : *list)
      if (s.face >= 0) s.a = move(piece[s.face], s.a), s.b = move(piece[s.face], s.b);
  for (Label& l : layout.labels) {
    const auto part = static_cast<std::size_t>(piece[l.side.face]);
    l.at = move(part, l.at);
    l.angle = std::remainder(l.angle + placed.angle[part], 2 * std::numbers::pi);
    // Upright on the page: a label turned past a quarter turn reads better turned half round.
    if (std::cos(l.angle) < -1e-9) l.angle += std::numbers::pi;
  }
  // Piece numbers stay level (any turn of theirs fits their place: print/internal/piece_labels.h).
  for (Label& l : layout.piece_labels)
    if (l.side.face >= 0) l.at = move(static_cast<std::size_t>(piece[l.side.face]), l.at);
  int sheets = placed.sheets;
  auto window = [&](int k) {
    return std::pair{Vec2{k * (w + kSheetGap), 0}, Vec2{k * (w + kSheetGap) + w, h}};
  };

  // Glue strips beside their edge, in free paper of the sheets (print/strips.h); those that
  // find none are nested onto sheets of their own.
  if (!layout.strips.empty()) {
    std::vector<StripRequest> requests;
    for (const GlueStrip& g : layout.strips) {
      const EdgeSide a = layout.edges[g.edge].a;
      requests.push_back({g.edge, norm(g.corners[1] - g.corners[0]),
                          norm(g.corners[3] - g.corners[0]),
                          0.5 * (layout.faces[a.face][a.k] + layout.faces[a.face][(a.k + 1) % 3])});
    }
    StripOptions strip_options;
    strip_options.gap = 0.5 * spacing_mm;
    strip_options.nearest_in_box = true;  // on the sheet of its edge, wherever there is room
    for (int k = 0; k < sheets; ++k) strip_options.within.push_back(window(k));
    std::vector<GlueStrip> moved =
        place_strips(layout.faces, layout.tabs, requests, {}, strip_options);
    std::vector<Part> left;
    std::vector<std::size_t> left_index;
    std::map<int, const GlueStrip*> by_edge;  // the label each strip carries
    for (const GlueStrip& g : layout.strips) by_edge[g.edge] = &g;
    for (std::size_t i = 0; i < moved.size(); ++i) {
      moved[i].text = by_edge.at(moved[i].edge)->text;
      moved[i].text_size = by_edge.at(moved[i].edge)->text_size;
      bool held = false;
      for (const auto& [lo, hi] : strip_options.within) held = held || inside(moved[i], lo, hi);
      if (held) continue;
      left.push_back({{{moved[i].corners.begin(), moved[i].corners.end()}}, 0});
      left_index.push_back(i);
    }
    if (!left.empty()) {
      const Placement more = nest_parts(left, w, h, spacing_mm, sheets, options.paper.name);
      for (std::size_t j = 0; j < left.size(); ++j)
        for (Vec2& p : moved[left_index[j]].corners) p = rotate(p, more.angle[j]) + more.shift[j];
      sheets += more.sheets;
    }
    layout.strips = std::move(moved);
  }
  layout.size = {sheets * (w + kSheetGap) - kSheetGap, h};

  PageLayout out;
  out.width = options.paper.width;
  out.height = options.paper.height;
  out.margin = options.margin_mm;
  out.overlap = 0;
  out.fitted = true;
  out.rows = 1;
  out.cols = sheets;
  // The sheets in the order of the lowest piece each holds (pieces are numbered in build order:
  // print/build_order.h), so a kit is built page after page; sheets of strips only last.
  std::vector<int> lowest(static_cast<std::size_t>(sheets), std::numeric_limits<int>::max());
  for (std::size_t f = 0; f < layout.faces.size(); ++f) {
    const auto& t = layout.faces[f];
    const double x = (t[0].x + t[1].x + t[2].x) / 3;
    const int k = std::clamp(static_cast<int>(std::floor(x / (w + kSheetGap))), 0, sheets - 1);
    lowest[k] = std::min(lowest[k], piece[f]);
  }
  std::vector<int> order(static_cast<std::size_t>(sheets));
  for (int k = 0; k < sheets; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return lowest[a] < lowest[b]; });
  for (int i = 0; i < sheets; ++i)
    out.pages.push_back({0, i, window(order[i]).first, window(order[i]).second});
  return out;
}

}  // namespace papernet
