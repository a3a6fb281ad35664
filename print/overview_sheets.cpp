// The overview's sheets drawn small, each piece's number on its thumbnail, and the views of the
// model, as a grid of captioned cells (print/internal/overview_parts.h).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "print/internal/grid_cells.h"
#include "print/internal/overview_parts.h"
#include "print/internal/page_boxes.h"
#include "print/tabs.h"

namespace papernet::print_detail {
namespace {

constexpr double kPieceMm = 4;    // a piece's number on its sheet's thumbnail
constexpr double kViewDpi = 150;  // the views of the model (the overview is on plain paper)
// The longest side of a thumbnail (and so of the views of the model), mm: on paper far larger
// than A3 (a plotter's) the overview's thumbnails stay this size, where they grew with the page
// (on 3 x 3 m paper, views of 1.4 m painted at 150 dpi three times finer: 2 GB and 24 s).
constexpr double kMostThumbMm = 250;

using Box = PageBox;

// Cells of a thumbnail, for finding the lines and faces near a place.
constexpr double kCellMm = 4;

/// Calls `f` with the key of each cell of the bounding box of `points`.
template <class F>
void for_cells(std::span<const Vec2> points, F&& f) {
  for_each_cell_key(points, kCellMm, f);
}

/// The cut lines drawn on a thumbnail, on a grid of cells.
class Lines {
 public:
  void add(Vec2 a, Vec2 b) {
    const auto i = static_cast<int>(lines_.size());
    lines_.push_back({a, b});
    for_cells(lines_.back(), [&](std::uint64_t key) { cells_[key].push_back(i); });
  }
  /// True when a line meets `box`.
  bool cross(const Box& box) const {
    bool hit = false;
    for_cells(box.corners(), [&](std::uint64_t key) {
      const auto it = cells_.find(key);
      if (hit || it == cells_.end()) return;
      for (const int i : it->second)
        if (box.crosses(lines_[i][0], lines_[i][1])) {
          hit = true;
          return;
        }
    });
    return hit;
  }

 private:
  std::vector<std::array<Vec2, 2>> lines_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

/// True when `p` lies in the triangle `t` (either orientation, sides included).
bool in_triangle(Vec2 p, const std::array<Vec2, 3>& t) {
  const double c0 = cross(t[1] - t[0], p - t[0]), c1 = cross(t[2] - t[1], p - t[1]);
  const double c2 = cross(t[0] - t[2], p - t[2]);
  return (c0 >= 0 && c1 >= 0 && c2 >= 0) || (c0 <= 0 && c1 <= 0 && c2 <= 0);
}

/// The paper of the pieces drawn on a thumbnail (faces and tabs as triangles), on a grid.
class Paper {
 public:
  void add(const std::array<Vec2, 3>& t, int piece) {
    const auto i = static_cast<int>(triangles_.size());
    triangles_.push_back({t, piece});
    for_cells(t, [&](std::uint64_t key) { cells_[key].push_back(i); });
  }
  /// True when `p` lies on the paper of a piece other than `piece`.
  bool elsewhere(Vec2 p, int piece) const {
    bool on = false;
    for_cells(std::span<const Vec2>(&p, 1), [&](std::uint64_t key) {
      const auto it = cells_.find(key);
      if (it == cells_.end()) return;
      for (const int i : it->second)
        if (triangles_[i].second != piece && in_triangle(p, triangles_[i].first)) on = true;
    });
    return on;
  }

 private:
  std::vector<std::pair<std::array<Vec2, 3>, int>> triangles_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

// Rings out to which a piece's number looks for a place on its piece or beside it (about 12 mm
// from its label at 4 mm), where a line back to it still reads as its.
constexpr int kNearRings = 4;

// The sizes a piece's number takes on its thumbnail, largest first: a small piece's number
// shrinks to print on it clear of its cut lines.
constexpr std::array<double, 3> kPieceSizesMm{kPieceMm, 3, 2.5};

/// A piece's number on its thumbnail: where, and how large.
struct Placed {
  Vec2 at;
  double size = kPieceMm;
  Vec2 half;  ///< half-size of its box
};

/// Where the number `name` of piece `piece` goes on its thumbnail, and how large. Its box must
/// overlap none of `taken`; the first of these found is taken: the place nearest `at` (its
/// piece's label) where the box crosses no cut line of `lines` and its centre is on no other
/// piece of `paper` (on its own piece, or beside it on free paper), at each size of
/// kPieceSizesMm in turn, within kNearRings, then anywhere out to the far side of `inside`; then
/// the nearest place clear of the lines over another piece, at the smallest size; then at the
/// largest size the nearest place on no other piece, within kNearRings, that may cross lines;
/// then the nearest place at all; `at` when none is free. Away from `at`, the caller draws a
/// line back to it.
Placed place_number(const std::string& name, int piece, Vec2 at, const Box& inside,
                    const std::vector<Box>& taken, const Lines& lines, const Paper& paper) {
  const auto apart = [&](const Box& box) {
    return std::none_of(taken.begin(), taken.end(), [&](const Box& t) { return t.overlaps(box); });
  };
  const auto near = [&](const Box& box) {
    return apart(box) &&
           !paper.elsewhere(Vec2{0.5 * (box.x0 + box.x1), 0.5 * (box.y0 + box.y1)}, piece);
  };
  const auto clear = [&](const Box& box) { return near(box) && !lines.cross(box); };
  const auto half_of = [&](double size) {
    return Vec2{0.5 * text_width(name, size) + 0.3, 0.5 * size + 0.3};
  };
  const auto rings_of = [&](Vec2 half) {
    const double reach =
        (inside.x1 - inside.x0) / (2 * half.x) + (inside.y1 - inside.y0) / (2 * half.y);
    return std::max(kNearRings, static_cast<int>(std::ceil(reach)));
  };
  for (const bool far : {false, true})
    for (const double size : kPieceSizesMm) {
      const Vec2 half = half_of(size);
      if (const std::optional<Vec2> place =
              ring_place(at, half, inside, far ? rings_of(half) : kNearRings, clear))
        return {*place, size, half};
    }
  // Over another piece, clear of its lines, at the smallest size.
  const Vec2 small = half_of(kPieceSizesMm.back());
  const auto between = [&](const Box& box) { return apart(box) && !lines.cross(box); };
  if (const std::optional<Vec2> place = ring_place(at, small, inside, rings_of(small), between))
    return {*place, kPieceSizesMm.back(), small};
  const Vec2 half = half_of(kPieceMm);
  if (const std::optional<Vec2> place = ring_place(at, half, inside, kNearRings, near))
    return {*place, kPieceMm, half};
  return {ring_place(at, half, inside, rings_of(half), apart).value_or(at), kPieceMm, half};
}

/// The views of the model in the box [lo, hi] (page mm, y down): from the front, from above
/// and to the right, then from the opposite side (the back, from below), one above the other in
/// a tall box, else side by side, each piece's number on it (draw_model_view).
void draw_views(const Overview& overview, Vec2 lo, Vec2 hi, Writer& out) {
  const Vec3 up = overview.axes.up, front = overview.axes.front;
  const Vec3 toward = front + 0.8 * cross(up, front) + 0.6 * up;
  const Vec2 size = hi - lo;
  const bool stacked = size.y >= size.x;
  const Vec2 step = stacked ? Vec2{0, 0.5 * (size.y + kGapMm)} : Vec2{0.5 * (size.x + kGapMm), 0};
  const Vec2 each =
      stacked ? Vec2{size.x, 0.5 * (size.y - kGapMm)} : Vec2{0.5 * (size.x - kGapMm), size.y};
  for (int v = 0; v < 2; ++v) {
    const Vec2 at = lo + static_cast<double>(v) * step;
    const ModelView view =
        draw_model_view(overview.model, overview.piece, v == 0 ? toward : -1.0 * toward, up, at,
                        at + each, kViewDpi, overview.colour);
    if (!view.image.surface) continue;
    out.d.images.push_back(view.image);
    for (const ModelView::Number& n : view.numbers) {
      out.text(Layer::Labels, n.at, piece_name(n.piece), n.size);
      if (!(n.from == n.to)) out.line(Layer::Marks, {n.from, n.to});
    }
  }
}

}  // namespace

std::vector<std::string> Cells::caption(std::size_t i, double cell_w) const {
  if (i == sheets.size()) {
    const std::string one = "the model, front and back";
    return text_width(one, text) <= cell_w
               ? std::vector<std::string>{one}
               : std::vector<std::string>{"the model,", "front and back"};
  }
  const std::string head = std::string("page ") + std::to_string(sheets[i] + 1) + ":";
  return on_sheet[i].empty() ? std::vector<std::string>{head + " glue strips"}
                             : wrap(head, on_sheet[i], cell_w, text);
}

double Cells::caption_height(double cell_w) const {
  std::size_t lines = 1;
  for (int i = 0; i < count(); ++i)
    lines = std::max(lines, caption(static_cast<std::size_t>(i), cell_w).size());
  return static_cast<double>(lines + 1) * kLinePitch * text;
}

Cells cells_of(const PageLayout& pages, const Overview& overview, double text) {
  Cells c;
  c.text = text;
  for (int k = 0; k < static_cast<int>(pages.pages.size()); ++k)
    if (!pages.pages[k].overview) c.sheets.push_back(k);
  c.on_sheet.resize(c.sheets.size());
  for (int p = 0; p < static_cast<int>(overview.page.size()); ++p)
    for (std::size_t i = 0; i < c.sheets.size(); ++i)
      if (overview.page[p] == c.sheets[i]) c.on_sheet[i].push_back(p);
  c.views = !overview.model.faces.empty() && overview.model.faces.size() == overview.piece.size();
  if (!c.sheets.empty()) {
    const Page& any = pages.pages[c.sheets.front()];
    c.sw = any.hi.x - any.lo.x;
    c.sh = any.hi.y - any.lo.y;
  }
  return c;
}

Grid grid_of(const Cells& cells, double width, int cols, double scale) {
  Grid g;
  g.cols = cols;
  g.cell_w = (width - (cols - 1) * kGapMm) / cols;
  g.caption = cells.caption_height(g.cell_w);
  g.scale = scale;
  g.cell_h = cells.sh * scale + g.caption;
  return g;
}

double most_scale(const Cells& cells) { return kMostThumbMm / std::max(cells.sw, cells.sh); }

Grid fit_grid(const Cells& cells, double width, double room) {
  Grid best;
  const int n = cells.count();
  for (int c = 1; c <= n; ++c) {
    const int r = (n + c - 1) / c;
    const double cell_w = (width - (c - 1) * kGapMm) / c;
    const double cell_h = (room - (r - 1) * kGapMm) / r - cells.caption_height(cell_w);
    const double s = std::min({cell_w / cells.sw, cell_h / cells.sh, most_scale(cells)});
    if (s > best.scale) best = grid_of(cells, width, c, s);
  }
  return best;
}

/// Draws the cells [first, last) of the grid, row by row from `top`: each sheet as a thumbnail
/// (its printable area dashed, its cut lines and strips, each piece's number), the views of the
/// model, each captioned.
void draw_cells(const PrintLayout& layout, const PageLayout& pages, const Overview& overview,
                const Cells& cells, const Grid& grid, int first, int last, double top,
                Writer& out) {
  const double m = pages.margin, width = pages.width - 2 * m;
  const double sw = cells.sw, sh = cells.sh, scale = grid.scale, cell_w = grid.cell_w;
  const int cols = grid.cols;
  const double left = m + 0.5 * (width - cols * cell_w - (cols - 1) * kGapMm);
  for (int i = first; i < last; ++i) {
    const double x0 = left + ((i - first) % cols) * (cell_w + kGapMm) + 0.5 * (cell_w - sw * scale);
    const double y0 = top + ((i - first) / cols) * (grid.cell_h + kGapMm);
    // The caption: "page 3: P1, P4", broken into lines that fit the thumbnail's width.
    const std::vector<std::string> lines = cells.caption(static_cast<std::size_t>(i), cell_w);
    for (std::size_t l = 0; l < lines.size(); ++l)
      out.text(Layer::Labels,
               {x0 + 0.5 * sw * scale,
                y0 + sh * scale + (static_cast<double>(l) + 1) * kLinePitch * cells.text},
               lines[l], cells.text);
    if (i == static_cast<int>(cells.sheets.size())) {
      draw_views(overview, {x0, y0}, {x0 + sw * scale, y0 + sh * scale}, out);
      continue;
    }
    const Page& page = pages.pages[cells.sheets[i]];
    auto map = [&](Vec2 p) {
      return Vec2{x0 + (p.x - page.lo.x) * scale, y0 + (page.hi.y - p.y) * scale};
    };
    // The printable area, dashed: four lines (the SVG fills the marks layer's shapes for its
    // text, so no polygon there).
    const std::array<Vec2, 4> corner{{{x0, y0},
                                      {x0 + sw * scale, y0},
                                      {x0 + sw * scale, y0 + sh * scale},
                                      {x0, y0 + sh * scale}}};
    for (int k = 0; k < 4; ++k) out.line(Layer::Marks, {corner[k], corner[(k + 1) % 4]});
    Lines cuts;
    for (const Segment& s : layout.cut)
      if (holds(page, s.a) && holds(page, s.b)) {
        out.line(Layer::Cut, {map(s.a), map(s.b)});
        cuts.add(map(s.a), map(s.b));
      }
    for (const GlueStrip& g : layout.strips)
      if (std::all_of(g.corners.begin(), g.corners.end(), [&](Vec2 p) { return holds(page, p); })) {
        out.line(Layer::Cut, {map(g.corners[0]), map(g.corners[1]), map(g.corners[2]),
                              map(g.corners[3]), map(g.corners[0])});
        for (int k = 0; k < 4; ++k) cuts.add(map(g.corners[k]), map(g.corners[(k + 1) % 4]));
      }
    // Each piece's number at its label, or, where it would cover a number already there or
    // cross a cut line (a small piece), at the nearest place around it inside the thumbnail on
    // its piece or on free paper, with a line back to the piece.
    const Box inside{x0, y0, x0 + sw * scale, y0 + sh * scale};
    // The paper of each piece on the sheet, as drawn: its faces and its tabs (two triangles).
    Paper paper;
    const auto piece_of = [&](int face) {
      return face >= 0 && face < static_cast<int>(overview.piece.size()) ? overview.piece[face]
                                                                         : -1;
    };
    for (std::size_t f = 0; f < layout.faces.size(); ++f) {
      const auto& t = layout.faces[f];
      if (holds(page, (1.0 / 3) * (t[0] + t[1] + t[2])))
        paper.add({map(t[0]), map(t[1]), map(t[2])}, piece_of(static_cast<int>(f)));
    }
    for (const Tab& t : layout.tabs) {
      const auto& c = t.corners;
      if (!holds(page, 0.25 * (c[0] + c[1] + c[2] + c[3]))) continue;
      paper.add({map(c[0]), map(c[1]), map(c[2])}, piece_of(t.side.face));
      paper.add({map(c[0]), map(c[2]), map(c[3])}, piece_of(t.side.face));
    }
    std::vector<Box> taken;
    for (const int p : cells.on_sheet[i]) {
      if (p >= static_cast<int>(layout.piece_labels.size())) continue;
      const Vec2 at = map(layout.piece_labels[p].at);
      const std::string name = piece_name(p);
      const Placed number = place_number(name, p, at, inside, taken, cuts, paper);
      const Vec2 place = number.at, half = number.half;
      taken.push_back({place.x - half.x, place.y - half.y, place.x + half.x, place.y + half.y});
      out.text(Layer::Labels, place, name, number.size);
      const Vec2 edge{std::clamp(at.x, place.x - half.x, place.x + half.x),
                      std::clamp(at.y, place.y - half.y, place.y + half.y)};
      if (norm(edge - at) > 0.5) out.line(Layer::Marks, {at, edge});
    }
  }
}

}  // namespace papernet::print_detail
