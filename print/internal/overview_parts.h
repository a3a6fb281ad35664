#pragma once
// The overview page's two parts (print/overview.cpp plans its pages and draws them): the sheets
// drawn small, with the views of the model, as a grid of captioned cells
// (print/overview_sheets.cpp), and the build order's steps flowed into columns
// (print/overview_steps.cpp).

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/vec.h"
#include "print/internal/page_window.h"
#include "print/layout.h"
#include "print/overview.h"
#include "print/pages.h"

namespace papernet::print_detail {

inline constexpr double kTextMm = 3;        // captions and the build order
inline constexpr double kGapMm = 6;         // between thumbnails
inline constexpr double kLinePitch = 1.5;   // line spacing, in text heights
inline constexpr double kStepIndent = 1.5;  // of a step's lines after its first, in text heights

/// The shapes of an overview page as they are added: text and lines.
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

// The sheets and the views (print/overview_sheets.cpp).

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
  std::vector<std::string> caption(std::size_t i, double cell_w) const;

  /// The room under a thumbnail: the most lines of a caption and one more.
  double caption_height(double cell_w) const;
};

/// The cells of the overview of `pages` (its sheets, their pieces), captioned at `text` mm.
Cells cells_of(const PageLayout& pages, const Overview& overview, double text);

/// The grid's shape: columns, the thumbnails' scale, and a cell's size with its caption.
struct Grid {
  int cols = 1;
  double scale = 0, caption = 0, cell_w = 0, cell_h = 0;
};

/// The grid of `cells` in `cols` columns across `width` mm, its thumbnails at `scale`.
Grid grid_of(const Cells& cells, double width, int cols, double scale);

/// The largest scale of a thumbnail: its longer side kMostThumbMm (print/overview_sheets.cpp).
double most_scale(const Cells& cells);

/// The grid that shows every cell in `room` (mm high) with the largest thumbnails.
Grid fit_grid(const Cells& cells, double width, double room);

/// Draws the cells [first, last) of the grid, row by row from `top`: each sheet as a thumbnail
/// (its printable area dashed, its cut lines and strips, each piece's number), the views of the
/// model, each captioned.
void draw_cells(const PrintLayout& layout, const PageLayout& pages, const Overview& overview,
                const Cells& cells, const Grid& grid, int first, int last, double top, Writer& out);

// The build order (print/overview_steps.cpp).

/// `head` then the names of `pieces`, broken into lines no wider than `width` at `size`, the
/// lines after the first `indent` mm narrower.
std::vector<std::string> wrap(const std::string& head, const std::vector<int>& pieces, double width,
                              double size, double indent = 0);

/// `text` broken at its spaces into lines no wider than `width` at `size` (a word wider than that
/// on a line of its own; a no-break space does not break).
std::vector<std::string> wrap_words(const std::string& text, double width, double size);

/// The build order's steps in `columns` columns on a page `width` wide at `size`, each as its
/// lines (broken at their spaces only in one column, where even a step's first line is wider
/// than the page).
std::vector<std::vector<std::string>> column_steps(const Overview& overview, double width,
                                                   double size, int columns);

/// A line of the build order: its text (empty: a column's foot left blank), and whether it goes
/// on with a step begun on the line above (then indented by kStepIndent text heights).
struct StepLine {
  std::string text;
  bool continued = false;
};

/// The build order's lines at `size` in `columns` columns on a page `width` wide.
std::vector<StepLine> step_lines(const Overview& overview, double width, double size, int columns);

/// How far the build order's steps have flowed down the columns: the step, and its lines placed.
struct StepFlow {
  std::size_t step = 0, line = 0;
};

/// Flows `steps` on from `at` down `columns` columns of `rows` lines and says where they stop,
/// appending their lines to `lines` when given. A step that a column holds whole is never split
/// between two: it goes on to the next column, the rest of its own left blank (empty lines).
StepFlow flow_steps(const std::vector<std::vector<std::string>>& steps, StepFlow at, int columns,
                    int rows, std::vector<StepLine>* lines);

/// The columns of the build order at text height `size` on a page `width` wide: those that take
/// the fewest rows (the fewest of them for as many rows), no step's first line wider than its
/// column; with `break_steps`, long steps broken onto more lines in narrower columns, else the
/// most columns where no step is broken (but for a step wider than the page).
int step_columns(const Overview& overview, double width, double size, bool break_steps);

}  // namespace papernet::print_detail
