#include "print/overview.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "print/internal/grid_cells.h"
#include "print/internal/page_boxes.h"
#include "print/tabs.h"

namespace papernet {
namespace {

constexpr double kTextMm = 3;      // captions and the build order
constexpr double kSmallestMm = 2;  // they shrink to this at most, on a crowded overview
constexpr double kTitleMm = 5;
constexpr double kPieceMm = 4;       // a piece's number on its sheet's thumbnail
constexpr double kGapMm = 6;         // between thumbnails
constexpr double kLinePitch = 1.5;   // line spacing, in text heights
constexpr double kTitlePitch = 1.2;  // the title's, when it takes more than a line
constexpr double kStepGap = 4;       // between columns of the build order, in text heights
constexpr double kStepIndent = 1.5;  // of a step's lines after its first, in text heights
constexpr double kViewDpi = 150;     // the views of the model (the overview is on plain paper)
// The longest side of a thumbnail (and so of the views of the model), mm: on paper far larger
// than A3 (a plotter's) the overview's thumbnails stay this size, where they grew with the page
// (on 3 x 3 m paper, views of 1.4 m painted at 150 dpi three times finer: 2 GB and 24 s).
constexpr double kMostThumbMm = 250;

bool holds(const Page& page, Vec2 p) {
  return p.x >= page.lo.x && p.x <= page.hi.x && p.y >= page.lo.y && p.y <= page.hi.y;
}

/// `head` then the names of `pieces`, broken into lines no wider than `width` at `size`, the
/// lines after the first `indent` mm narrower.
std::vector<std::string> wrap(const std::string& head, const std::vector<int>& pieces, double width,
                              double size, double indent = 0) {
  std::vector<std::string> lines{head};
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const std::string name = piece_name(pieces[i]) + (i + 1 < pieces.size() ? "," : "");
    std::string& line = lines.back();
    const std::string longer = line + " " + name;
    const double room = lines.size() > 1 ? width - indent : width;
    if (line.size() > head.size() && text_width(longer, size) > room)
      lines.push_back(name);
    else
      line = longer;
  }
  return lines;
}

using Box = print_detail::PageBox;
using print_detail::ring_place;

// Cells of a thumbnail, for finding the lines and faces near a place.
constexpr double kCellMm = 4;

/// Calls `f` with the key of each cell of the bounding box of `points`.
template <class F>
void for_cells(std::span<const Vec2> points, F&& f) {
  print_detail::for_each_cell_key(points, kCellMm, f);
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

struct Writer {
  PageDrawing& d;
  void text(Layer layer, Vec2 centre, std::string s, double size) {
    d.shapes.push_back({layer, {centre}, false, std::move(s), size, 0});
  }
  /// Text starting at `start` (the middle of its left end).
  void text_from(Layer layer, Vec2 start, std::string s, double size) {
    Shape shape{layer, {start}, false, std::move(s), size, 0};
    shape.start = true;
    d.shapes.push_back(std::move(shape));
  }
  void line(Layer layer, std::vector<Vec2> points) {
    d.shapes.push_back({layer, std::move(points), false, {}, 0, 0});
  }
};

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

/// The cells of the overview's grid: each sheet (a page of pieces or strips) drawn small, and
/// last the views of the model (when the overview has them).
struct Cells {
  std::vector<int> sheets;                 ///< indices into pages.pages
  std::vector<std::vector<int>> on_sheet;  ///< the pieces on each
  bool views = false;
  double sw = 0, sh = 0;  ///< a sheet's printable area, mm
  double text = kTextMm;  ///< the captions' text height

  int count() const { return static_cast<int>(sheets.size()) + (views ? 1 : 0); }

  /// Cell i's caption ("page 3: P1, P4" or the views'), in lines that fit `cell_w` at `text`.
  std::vector<std::string> caption(std::size_t i, double cell_w) const {
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

  /// The room under a thumbnail: the most lines of a caption and one more.
  double caption_height(double cell_w) const {
    std::size_t lines = 1;
    for (int i = 0; i < count(); ++i)
      lines = std::max(lines, caption(static_cast<std::size_t>(i), cell_w).size());
    return static_cast<double>(lines + 1) * kLinePitch * text;
  }
};

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

/// The grid's shape: columns, the thumbnails' scale, and a cell's size with its caption.
struct Grid {
  int cols = 1;
  double scale = 0, caption = 0, cell_w = 0, cell_h = 0;
};

Grid grid_of(const Cells& cells, double width, int cols, double scale) {
  Grid g;
  g.cols = cols;
  g.cell_w = (width - (cols - 1) * kGapMm) / cols;
  g.caption = cells.caption_height(g.cell_w);
  g.scale = scale;
  g.cell_h = cells.sh * scale + g.caption;
  return g;
}

/// The largest scale of a thumbnail: kMostThumbMm on its longer side.
double most_scale(const Cells& cells) { return kMostThumbMm / std::max(cells.sw, cells.sh); }

/// The grid that shows every cell in `room` (mm high) with the largest thumbnails.
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

/// `text` broken at its spaces into lines no wider than `width` at `size` (a word wider than that
/// on a line of its own; a no-break space does not break).
std::vector<std::string> wrap_words(const std::string& text, double width, double size) {
  std::vector<std::string> lines;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find(' ', at), text.size());
    const std::string word = text.substr(at, end - at);
    if (!lines.empty() && text_width(lines.back() + " " + word, size) <= width)
      lines.back() += " " + word;
    else
      lines.push_back(word);
    at = end + 1;
  }
  return lines;
}

/// The build order's steps, each as lines no wider than `width` at `size` (the lines after a
/// step's first kStepIndent text heights narrower, to be indented): "P3 glues to P1, P2" (the
/// pieces before it that it shares an edge with), broken after a comma onto more lines where it
/// is wider ("P3 glues to P1," at least on its first; with `at_spaces`, at every space where even
/// that is wider), "P1: start here", "P7: start a new part".
std::vector<std::vector<std::string>> build_steps(const Overview& overview, double width,
                                                  double size, bool at_spaces) {
  std::vector<std::vector<std::string>> steps;
  const int count = static_cast<int>(overview.page.size());
  for (int p = 0; p < count; ++p) {
    std::vector<int> earlier;
    for (const int q : overview.graph.joins[p])
      if (q < p) earlier.push_back(q);
    std::vector<std::string> step =
        p == 0 ? std::vector{piece_name(p) + ": start here"}
        : earlier.empty()
            ? std::vector{piece_name(p) + ": start a new part"}
            : wrap(piece_name(p) + " glues to", earlier, width, size, kStepIndent * size);
    // On paper too narrow for its first line, at every space (every line as narrow as those
    // indented).
    if (at_spaces && text_width(step.front(), size) > width) {
      std::string text;
      for (const std::string& line : step) text += (text.empty() ? "" : " ") + line;
      step = wrap_words(text, width - kStepIndent * size, size);
    }
    steps.push_back(std::move(step));
  }
  return steps;
}

// The most columns of the build order on a page.
constexpr int kMostStepColumns = 8;

/// The width of the build order's lines in `columns` columns on a page `width` wide at `size`:
/// each column kStepGap text heights wider than its lines.
double step_room(double width, double size, int columns) {
  return width / columns - kStepGap * size;
}

/// The build order's steps in `columns` columns (build_steps; broken at their spaces only in one
/// column, where even a step's first line is wider than the page).
std::vector<std::vector<std::string>> column_steps(const Overview& overview, double width,
                                                   double size, int columns) {
  return build_steps(overview, step_room(width, size, columns), size, columns == 1);
}

/// A line of the build order: its text (empty: a column's foot left blank), and whether it goes
/// on with a step begun on the line above (then indented by kStepIndent text heights).
struct StepLine {
  std::string text;
  bool continued = false;
};

/// The build order's lines at `size` in `columns` columns on a page `width` wide.
std::vector<StepLine> step_lines(const Overview& overview, double width, double size, int columns) {
  std::vector<StepLine> lines;
  for (std::vector<std::string>& step : column_steps(overview, width, size, columns))
    for (std::size_t i = 0; i < step.size(); ++i) lines.push_back({std::move(step[i]), i > 0});
  return lines;
}

/// How far the build order's steps have flowed down the columns: the step, and its lines placed.
struct StepFlow {
  std::size_t step = 0, line = 0;
};

/// Flows `steps` on from `at` down `columns` columns of `rows` lines and says where they stop,
/// appending their lines to `lines` when given. A step that a column holds whole is never split
/// between two: it goes on to the next column, the rest of its own left blank (empty lines).
StepFlow flow_steps(const std::vector<std::vector<std::string>>& steps, StepFlow at, int columns,
                    int rows, std::vector<StepLine>* lines) {
  const auto whole = static_cast<std::size_t>(rows);
  for (int c = 0; c < columns && at.step < steps.size(); ++c) {
    std::size_t left = whole;
    while (left > 0 && at.step < steps.size()) {
      const std::vector<std::string>& step = steps[at.step];
      const std::size_t rest = step.size() - at.line;
      if (rest > left && at.line == 0 && step.size() <= whole && left < whole) break;
      const std::size_t take = std::min(rest, left);
      if (lines)
        for (std::size_t i = at.line; i < at.line + take; ++i) lines->push_back({step[i], i > 0});
      left -= take;
      at.line += take;
      if (at.line == step.size()) at = {at.step + 1, 0};
    }
    if (lines && c + 1 < columns && at.step < steps.size())
      lines->insert(lines->end(), left, StepLine{});
  }
  return at;
}

/// The columns of the build order at text height `size` on a page `width` wide: those that take
/// the fewest rows (the fewest of them for as many rows), no step's first line wider than its
/// column; with `break_steps`, long steps broken onto more lines in narrower columns, else the
/// most columns where no step is broken (but for a step wider than the page).
int step_columns(const Overview& overview, double width, double size, bool break_steps) {
  int best = 1;
  std::size_t best_rows = std::numeric_limits<std::size_t>::max();
  for (int columns = 1; columns <= kMostStepColumns; ++columns) {
    const double room = step_room(width, size, columns);
    std::size_t lines = 0;
    bool fits = true, whole = true;
    for (const std::vector<std::string>& step : column_steps(overview, width, size, columns)) {
      fits = fits && text_width(step.front(), size) <= room;
      whole = whole && step.size() == 1;
      lines += step.size();
    }
    if (columns > 1 && !(fits && (whole || break_steps))) break;
    const std::size_t rows = (lines + columns - 1) / columns;
    if (rows < best_rows) best = columns, best_rows = rows;
    if (lines <= static_cast<std::size_t>(columns)) break;  // one row: no fewer
  }
  return best;
}

/// The header of an overview page, each line broken to fit the printable width: the title
/// (kTitleMm) and, on the first page, how to read the labels and the folds (kTextMm).
struct Header {
  std::vector<std::string> title, lines;

  /// The title's lines' centres from the page's top margin `m` down, then the others'.
  double title_y(double m, std::size_t i) const {
    return m + 0.5 * kTitleMm + static_cast<double>(i) * kTitlePitch * kTitleMm;
  }
  double line_y(double m, std::size_t i) const {
    return title_y(m, title.size() - 1) + kTitleMm +
           static_cast<double>(i + 1) * kLinePitch * kTextMm;
  }
  /// Where what follows it begins.
  double bottom(double m) const {
    return lines.empty() ? title_y(m, title.size() - 1) + kTitleMm + 2
                         : line_y(m, lines.size() - 1) + kTextMm + 2;
  }
  /// Whether every line fits `width` (no word wider than it).
  bool fits(double width) const {
    const auto narrow = [&](double size) {
      return [&, size](const std::string& l) { return text_width(l, size) <= width; };
    };
    return std::all_of(title.begin(), title.end(), narrow(kTitleMm)) &&
           std::all_of(lines.begin(), lines.end(), narrow(kTextMm));
  }
};

/// The header of the first page of an overview of `pieces` pieces on `sheets` sheets, titled
/// with the kit's `name` where it has one; with `folds`, its last line says which way the folds
/// go.
Header first_header(const std::string& name, int pieces, int sheets, double width, bool folds) {
  const std::string title = (name.empty() ? std::string("Overview") : name) + ": " +
                            std::to_string(pieces) + (pieces == 1 ? " piece on " : " pieces on ") +
                            std::to_string(sheets) + (sheets == 1 ? " sheet" : " sheets");
  Header h{wrap_words(title, width, kTitleMm), {}};
  std::vector<const char*> lines = {
      "Cut out each piece along its solid lines; build in order P1,\u00a0P2,\u00a0P3,\u00a0...",
      "An edge labelled 12\u2192P3 glues to edge 12 of piece P3."};
  if (folds)
    lines.push_back(
        "Fold dashed lines away from you (mountain folds), dash-dotted lines towards you (valley "
        "folds).");
  for (const char* line : lines)
    for (std::string& l : wrap_words(line, width, kTextMm)) h.lines.push_back(std::move(l));
  return h;
}

/// The header of overview page `which` + 1 of `parts` (which > 0).
Header next_header(int which, int parts, double width) {
  return {wrap_words("Overview, continued (" + std::to_string(which + 1) + " of " +
                         std::to_string(parts) + ")",
                     width, kTitleMm),
          {}};
}

// The least width of a thumbnail on a one-page overview, mm: below it the overview continues on
// more pages with thumbnails kFlowCellMm wide.
constexpr double kLeastThumbMm = 25;
constexpr double kFlowCellMm = 32;
constexpr double kFlowTextMm = 2.5;
// The sizes an overview of several pages tries, thumbnails (the least width that sets how many
// to a row, mm) and text (mm high): the first unless a later one takes fewer pages.
constexpr std::array<std::pair<double, double>, 3> kFlowSizes{
    {{kFlowCellMm, kFlowTextMm}, {kFlowCellMm, kSmallestMm}, {kLeastThumbMm, kSmallestMm}}};
// The least size of a thumbnail on an overview of several pages (its longer side), mm: below
// it the overview is left out (its pieces' numbers would not fit it).
constexpr double kLeastFlowThumbMm = 20;
// The build order's heading where it goes on from a page before, and its size in the lines'.
constexpr const char* kStepsContinued = "Build order, continued";
constexpr double kHeadingScale = 1.3;
// The fewest lines of the build order a page of the overview after the first holds.
constexpr int kLeastSteps = 3;

}  // namespace

/// What each overview page shows: cells of the grid and lines of the build order.
struct OverviewPlan {
  struct Part {
    int first_cell = 0, last_cell = 0;
    double grid_top = 0;
    int first_step = 0, last_step = 0;  ///< of `steps`, the build order's lines
    int rows = 0;  ///< of the build order on this page (its lines column by column)
    double steps_top = 0;
  };
  Grid grid;
  double text = kTextMm;  ///< the captions'
  double step_size = kTextMm;
  int columns = 1;
  bool folds = true;  ///< the first page's header says which way the folds go (first_header)
  /// The first page's title's name: the kit's (PageLayout::title), or empty ("Overview") where
  /// a word of it is wider than the page.
  std::string name;
  /// The build order's lines, column by column.
  std::vector<StepLine> steps;
  std::vector<Part> parts;  ///< one per overview page
};

namespace {

/// The overview over several pages: rows of as many thumbnails as the width holds `cell` mm
/// wide (each as wide as the row then allows, less where a page is too low for it), while they
/// fit, then the build order's lines, continued on as many pages as they need, all its text
/// `text` mm high; none where the paper is too small for it (plan_overview). `plan` holds the
/// first page's header.
std::optional<OverviewPlan> plan_flow(const PageLayout& pages, const Overview& overview,
                                      OverviewPlan plan, double top, double next_top, double cell,
                                      double text) {
  const double m = pages.margin, width = pages.width - 2 * m, bottom = pages.height - m;
  plan.text = text;
  plan.columns = step_columns(overview, width, text, true);
  const std::vector<std::vector<std::string>> steps =
      column_steps(overview, width, text, plan.columns);
  const int count = static_cast<int>(steps.size());
  // The build order's heading on a page after the first.
  if (count > 0 && text_width(kStepsContinued, kHeadingScale * text) > width) return std::nullopt;
  const double pitch = kLinePitch * text;
  // Lines of the build order a page after the first holds: its title, a line of space.
  const auto lines_below = [&](double y) { return static_cast<int>((bottom - y) / pitch) - 2; };
  if (count > 0 && lines_below(next_top) < kLeastSteps) return std::nullopt;
  const Cells small = cells_of(pages, overview, text);
  const int n = small.count();
  OverviewPlan::Part part;
  part.grid_top = top;
  double y = top;
  if (n > 0) {
    const int cols = std::clamp(static_cast<int>((width + kGapMm) / (cell + kGapMm)), 1, n);
    Grid g = grid_of(small, width, cols, 0);
    // A row fits any page, the first (below its longer header) included.
    g.scale =
        std::min({g.cell_w / small.sw, (bottom - top - g.caption) / small.sh, most_scale(small)});
    if (!(g.scale * std::max(small.sw, small.sh) >= kLeastFlowThumbMm)) return std::nullopt;
    g.cell_h = small.sh * g.scale + g.caption;
    plan.grid = g;
    for (int first_cell = 0; first_cell < n; first_cell += cols) {
      if (y + g.cell_h > bottom && part.last_cell > part.first_cell) {
        plan.parts.push_back(part);
        part = {first_cell, first_cell, next_top, 0, 0, 0, 0};
        y = next_top;
      }
      part.last_cell = std::min(n, first_cell + cols);
      y += g.cell_h + kGapMm;
    }
  }
  plan.step_size = text;
  for (StepFlow at; at.step < steps.size();) {
    int room = lines_below(y);
    const int first = static_cast<int>(plan.steps.size());
    if (room < kLeastSteps) {
      plan.parts.push_back(part);
      part = {n, n, next_top, first, first, 0, 0};
      y = next_top;
      room = lines_below(y);
    }
    // The page's rows, or on the last page the fewest that hold the rest.
    int rows = room;
    for (int r = 1; r < room; ++r)
      if (flow_steps(steps, at, plan.columns, r, nullptr).step == steps.size()) {
        rows = r;
        break;
      }
    at = flow_steps(steps, at, plan.columns, rows, &plan.steps);
    part.first_step = first;
    part.last_step = static_cast<int>(plan.steps.size());
    part.rows = rows;
    part.steps_top = y;
    y = bottom;  // the page is full, or the build order ends here
  }
  plan.parts.push_back(part);
  return plan;
}

/// The overview's pages for `pages` (its overview pages first): everything on one page where
/// the thumbnails print at least kLeastThumbMm wide and the build order takes at most 40 % of it
/// at 2 mm or more; else the grid at kFlowCellMm a thumbnail and then the build order, their
/// text kFlowTextMm high, each continued on as many pages as it needs (plan_flow), or smaller
/// (kFlowSizes) where that takes fewer pages. None where the paper is too small for it: its
/// header's words wider than the printable area, a row of thumbnails kLeastFlowThumbMm large with
/// their captions taller than the first page holds below its header, or fewer than kLeastSteps
/// lines of the build order (or its heading wider than the printable area) on a page after the
/// first. A step of the build order wider than a column goes on on the lines below it. With
/// `folds`, the first page's header says which way the folds go.
std::optional<OverviewPlan> plan_overview(const PageLayout& pages, const Overview& overview,
                                          bool folds) {
  const double m = pages.margin, width = pages.width - 2 * m, bottom = pages.height - m;
  const Cells cells = cells_of(pages, overview, kTextMm);
  const int n = cells.count();
  const auto header = [&](const std::string& name) {
    return first_header(name, static_cast<int>(overview.page.size()),
                        static_cast<int>(cells.sheets.size()), width, folds);
  };
  std::string name = pages.title;
  Header first = header(name);
  if (!first.fits(width) && !name.empty()) {
    name.clear();
    first = header(name);
  }
  // The pages after the first: their title with the most digits it may print.
  const Header next = next_header(998, 999, width);
  if (!first.fits(width) || !next.fits(width)) return std::nullopt;
  const double top = first.bottom(m), next_top = next.bottom(m);
  OverviewPlan plan;
  plan.folds = folds;
  plan.name = name;
  // One page: the build order as small as it must be to take at most 40 % of the page, the
  // sheets as large as the room above it holds them.
  double size = kTextMm, block = 0;
  int columns = 1, rows = 0, count = 0;
  for (;; size = std::max(kSmallestMm, size - 0.25)) {
    columns = step_columns(overview, width, size, false);
    count = static_cast<int>(step_lines(overview, width, size, columns).size());
    rows = (count + columns - 1) / columns;
    block = (rows + 2) * kLinePitch * size;
    if (block <= 0.4 * (pages.height - 2 * m) || size <= kSmallestMm) break;
  }
  const Grid fitted = n > 0 ? fit_grid(cells, width, bottom - block - kGapMm - top) : Grid{};
  if (block <= 0.4 * (pages.height - 2 * m) &&
      (n == 0 || fitted.scale * cells.sw >= kLeastThumbMm)) {
    plan.grid = fitted;
    plan.step_size = size;
    plan.columns = columns;
    const int grid_rows = n > 0 ? (n + fitted.cols - 1) / fitted.cols : 0;
    const double foot =
        n > 0 ? top + grid_rows * fitted.cell_h + (grid_rows - 1) * kGapMm + kGapMm : top;
    plan.steps = step_lines(overview, width, size, columns);
    plan.parts.push_back({0, n, top, 0, count, rows, foot});
    return plan;
  }
  // Several pages: the fewest, the text and then the thumbnails smaller where that saves one
  // (a last page of a few lines of the build order).
  std::optional<OverviewPlan> fewest;
  for (const auto& [cell, text] : kFlowSizes) {
    std::optional<OverviewPlan> flow = plan_flow(pages, overview, plan, top, next_top, cell, text);
    if (flow && (!fewest || flow->parts.size() < fewest->parts.size())) fewest = std::move(flow);
  }
  return fewest;
}

}  // namespace

bool add_overview(PageLayout& pages, const PrintLayout& layout, const std::vector<int>& piece,
                  PieceGraph graph, Mesh model, ViewAxes axes, bool colour) {
  auto overview = std::make_shared<Overview>();
  int count = 0;
  for (const int p : piece) count = std::max(count, p + 1);
  // Each piece's sheet before the overview's pages go first.
  std::vector<int> sheet(static_cast<std::size_t>(count), -1);
  for (std::size_t f = 0; f < piece.size() && f < layout.faces.size(); ++f) {
    int& page = sheet[piece[f]];
    if (page >= 0) continue;
    const auto& t = layout.faces[f];
    const Vec2 centre = (1.0 / 3) * (t[0] + t[1] + t[2]);
    for (int k = 0; k < static_cast<int>(pages.pages.size()) && page < 0; ++k)
      if (holds(pages.pages[k], centre)) page = k;
  }
  overview->piece = piece;
  overview->graph = std::move(graph);
  if (model.faces.size() == layout.faces.size()) overview->model = std::move(model);
  overview->axes = axes;
  overview->colour = colour;
  Page first;
  first.overview = true;
  first.lo = {0, 0};
  first.hi = {-1, -1};
  // As many overview pages as its plan needs, which depends on the sheets' page numbers in the
  // captions: tried from one page until they agree.
  std::size_t added = 0;
  for (int round = 0; round < 8; ++round) {
    while (added < std::max<std::size_t>(1, overview->plan ? overview->plan->parts.size() : 1)) {
      pages.pages.insert(pages.pages.begin(), first);
      ++added;
    }
    while (overview->plan && added > overview->plan->parts.size()) {
      pages.pages.erase(pages.pages.begin());
      --added;
    }
    overview->page.assign(static_cast<std::size_t>(count), -1);
    for (int p = 0; p < count; ++p)
      if (sheet[p] >= 0) overview->page[p] = sheet[p] + static_cast<int>(added);
    // On small paper the line on the folds goes first (each sheet's key shows the lines).
    std::optional<OverviewPlan> plan = plan_overview(pages, *overview, true);
    if (!plan) plan = plan_overview(pages, *overview, false);
    if (!plan) {  // the paper is too small for it
      pages.pages.erase(pages.pages.begin(),
                        pages.pages.begin() + static_cast<std::ptrdiff_t>(added));
      return false;
    }
    overview->plan = std::make_shared<const OverviewPlan>(std::move(*plan));
    if (overview->plan->parts.size() == added) break;
  }
  // Never seen: the rounds did not agree. The pages follow the last plan (whose captions were
  // laid out with page numbers a digit shorter or longer than those they print).
  for (; added < overview->plan->parts.size(); ++added)
    pages.pages.insert(pages.pages.begin(), first);
  for (; added > overview->plan->parts.size(); --added) pages.pages.erase(pages.pages.begin());
  for (int p = 0; p < count; ++p)
    if (sheet[p] >= 0) overview->page[p] = sheet[p] + static_cast<int>(added);
  pages.overview = std::move(overview);
  return true;
}

PageDrawing draw_overview(const PrintLayout& layout, const PageLayout& pages, int index) {
  const double m = pages.margin, width = pages.width - 2 * m;
  PageDrawing d{pages.width, pages.height, {m, m}, {pages.width - m, pages.height - m}, {}, {}, {}};
  Writer out{d};
  const Overview& overview = *pages.overview;
  const OverviewPlan& plan = *overview.plan;
  const int count = static_cast<int>(overview.page.size());
  const Cells cells = cells_of(pages, overview, plan.text);
  int which = 0;  // this page's part of the overview
  for (int k = 0; k < index; ++k) which += pages.pages[k].overview ? 1 : 0;
  if (which >= static_cast<int>(plan.parts.size())) return d;
  const OverviewPlan::Part& part = plan.parts[which];

  // The title and how to read the labels; on the pages after the first, a title.
  const Header header = which > 0
                            ? next_header(which, static_cast<int>(plan.parts.size()), width)
                            : first_header(plan.name, count, static_cast<int>(cells.sheets.size()),
                                           width, plan.folds);
  for (std::size_t i = 0; i < header.title.size(); ++i)
    out.text(Layer::Labels, {0.5 * pages.width, header.title_y(m, i)}, header.title[i], kTitleMm);
  for (std::size_t i = 0; i < header.lines.size(); ++i)
    out.text(Layer::Labels, {0.5 * pages.width, header.line_y(m, i)}, header.lines[i], kTextMm);

  // The sheets as thumbnails, each captioned with its pieces (the sheet list), and the views.
  if (part.last_cell > part.first_cell)
    draw_cells(layout, pages, overview, cells, plan.grid, part.first_cell, part.last_cell,
               part.grid_top, out);

  // The build order, in columns, line by line down each column: each column's lines aligned
  // at their left, a step's lines after its first indented, the column's widest line centred.
  if (part.last_step > part.first_step) {
    const double size = plan.step_size, bottom = part.steps_top;
    const std::vector<StepLine>& steps = plan.steps;
    out.text(Layer::Labels, {0.5 * pages.width, bottom + 0.5 * kLinePitch * size + 1},
             part.first_step > 0 ? kStepsContinued : "Build order", kHeadingScale * size);
    const double column_width = width / plan.columns, indent = kStepIndent * size;
    const auto line_width = [&](const StepLine& l) {
      return text_width(l.text, size) + (l.continued ? indent : 0);
    };
    for (int begin = part.first_step; begin < part.last_step; begin += part.rows) {
      const int end = std::min(part.last_step, begin + part.rows),
                c = (begin - part.first_step) / part.rows;
      double widest = 0;
      for (int i = begin; i < end; ++i) widest = std::max(widest, line_width(steps[i]));
      const double left = m + (c + 0.5) * column_width - 0.5 * widest;
      for (int i = begin; i < end; ++i) {
        if (steps[i].text.empty()) continue;  // a column's foot left blank
        out.text_from(Layer::Labels,
                      {left + (steps[i].continued ? indent : 0),
                       bottom + (i - begin + 2) * kLinePitch * size},
                      steps[i].text, size);
      }
    }
  }
  return d;
}

}  // namespace papernet
