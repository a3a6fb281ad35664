#include "print/overview.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "print/internal/overview_parts.h"

namespace papernet {

using print_detail::Cells;
using print_detail::cells_of;
using print_detail::column_steps;
using print_detail::draw_cells;
using print_detail::fit_grid;
using print_detail::flow_steps;
using print_detail::Grid;
using print_detail::grid_of;
using print_detail::holds;
using print_detail::kGapMm;
using print_detail::kLinePitch;
using print_detail::kStepIndent;
using print_detail::kTextMm;
using print_detail::most_scale;
using print_detail::step_columns;
using print_detail::step_lines;
using print_detail::StepFlow;
using print_detail::StepLine;
using print_detail::wrap_words;
using print_detail::Writer;

namespace {

constexpr double kSmallestMm = 2;  // the overview's text shrinks to this at most, when crowded
constexpr double kTitleMm = 5;
constexpr double kTitlePitch = 1.2;  // the title's line spacing, when it takes more than a line

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
// The narrowest column of thumbnails and the most rows to a page the small paper's overview
// tries (plan_overview).
constexpr double kLeastSmallThumbMm = 15;
constexpr int kMostSmallRows = 4;
// The least area of such a thumbnail for each piece on its sheet, mm² (about a 12 mm square,
// where a piece's number "P12" prints 4 mm high): on A5 the Duck's 30 pieces, up to 5 on a
// sheet, would take one page with thumbnails 17 mm wide, their numbers over each other.
constexpr double kThumbMm2PerPiece = 150;
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

/// The shape of an overview of several pages: its thumbnails in rows of `cols` (each as wide as
/// a column, less where a page is too low for it), `rows` rows to a page after the first (0: as
/// many as fit), its text `text` mm high.
struct FlowSize {
  int cols = 1, rows = 0;
  double text = kFlowTextMm;
};

/// What an overview of several pages sets at one text size, whatever its thumbnails: the
/// build order's columns and their steps, and the cells captioned.
struct FlowText {
  double text = kFlowTextMm;
  int columns = 1;
  std::vector<std::vector<std::string>> steps;
  Cells cells;
};

FlowText flow_text(const PageLayout& pages, const Overview& overview, double text) {
  const double width = pages.width - 2 * pages.margin;
  FlowText t;
  t.text = text;
  t.columns = step_columns(overview, width, text, true);
  t.steps = column_steps(overview, width, text, t.columns);
  t.cells = cells_of(pages, overview, text);
  return t;
}

/// The overview over several pages: rows of thumbnails shaped by `size` while they fit, then
/// the build order's lines, continued on as many pages as they need; none where the paper is too
/// small for it (plan_overview). `plan` holds the first page's header; `set`, the text set at
/// `size.text`.
std::optional<OverviewPlan> plan_flow(const PageLayout& pages, OverviewPlan plan, double top,
                                      double next_top, FlowSize size, const FlowText& set) {
  const double text = size.text;
  const double m = pages.margin, width = pages.width - 2 * m, bottom = pages.height - m;
  plan.text = text;
  plan.columns = set.columns;
  const std::vector<std::vector<std::string>>& steps = set.steps;
  const int count = static_cast<int>(steps.size());
  // The build order's heading on a page after the first.
  if (count > 0 && text_width(kStepsContinued, kHeadingScale * text) > width) return std::nullopt;
  const double pitch = kLinePitch * text;
  // Lines of the build order a page after the first holds: its title, a line of space.
  const auto lines_below = [&](double y) { return static_cast<int>((bottom - y) / pitch) - 2; };
  if (count > 0 && lines_below(next_top) < kLeastSteps) return std::nullopt;
  const Cells& small = set.cells;
  const int n = small.count();
  OverviewPlan::Part part;
  part.grid_top = top;
  double y = top;
  if (n > 0) {
    Grid g = grid_of(small, width, std::clamp(size.cols, 1, n), 0);
    const int cols = g.cols;
    // A row fits any page, the first (below its longer header) included.
    g.scale =
        std::min({g.cell_w / small.sw, (bottom - top - g.caption) / small.sh, most_scale(small)});
    if (size.rows > 0)
      g.scale = std::min(
          g.scale, ((bottom - next_top + kGapMm) / size.rows - kGapMm - g.caption) / small.sh);
    if (!(g.scale * std::max(small.sw, small.sh) >= kLeastFlowThumbMm)) return std::nullopt;
    // Thumbnails smaller than a column holds leave each piece's number room.
    if (size.rows > 0) {
      std::size_t crowded = 1;
      for (const std::vector<int>& on : small.on_sheet) crowded = std::max(crowded, on.size());
      if (g.scale * g.scale * small.sw * small.sh <
          kThumbMm2PerPiece * static_cast<double>(crowded))
        return std::nullopt;
    }
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
/// (kFlowSizes; then rows of thumbnails to a page, each leaving kThumbMm2PerPiece to a piece)
/// where that takes fewer pages. None where the paper is too small for it: its
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
  // (a last page of a few lines of the build order); then, for paper that holds a row of them
  // to a page, smaller thumbnails, more to a row or to a page, where that saves one (on 90 x 130
  // mm, 13 sheets took 7 pages of thumbnails, two to a page).
  std::vector<FlowSize> sizes;
  const auto columns_of = [&](double cell) {
    return std::max(1, static_cast<int>((width + kGapMm) / (cell + kGapMm)));
  };
  for (const auto& [cell, text] : kFlowSizes) sizes.push_back({columns_of(cell), 0, text});
  for (int cols = 1; cols <= std::min(n, columns_of(kLeastSmallThumbMm)); ++cols)
    for (int rows = 1; rows <= kMostSmallRows; ++rows) sizes.push_back({cols, rows, kSmallestMm});
  // The text set once for each size (the sizes' texts are kFlowSizes').
  std::vector<FlowText> sets;
  std::optional<OverviewPlan> fewest;
  for (const FlowSize& size : sizes) {
    auto set = std::find_if(sets.begin(), sets.end(),
                            [&](const FlowText& t) { return t.text == size.text; });
    if (set == sets.end()) set = sets.insert(sets.end(), flow_text(pages, overview, size.text));
    std::optional<OverviewPlan> flow = plan_flow(pages, plan, top, next_top, size, *set);
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
