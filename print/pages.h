#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "print/colour.h"
#include "print/layout.h"

namespace papernet {

/// A sheet of paper, portrait (width <= height), millimetres.
struct Paper {
  std::string name = "A4";
  double width = 210, height = 297;
};

/// The papers known by name: A4, A3, A5, Letter, Legal and Tabloid (ANSI B, 11 x 17 in).
const std::vector<Paper>& named_papers();

/// "A4, A3, A5, Letter, Legal, Tabloid, WxHmm": what parse_paper takes, for messages and help.
std::string paper_names();

/// Parses a paper of named_papers() (any case) or "WxHmm" / "WxH" in millimetres ("300x200mm";
/// its name is then written "300x200mm"). \throw InvalidOptionException naming the bad value.
Paper parse_paper(std::string_view text);

/// Parses a length: "200mm", "20cm", "8in", "150pt" or a bare number of millimetres.
/// \throw InvalidOptionException when it is not a positive finite length.
double parse_length_mm(std::string_view text);

/// How a net goes onto pages: cut into pieces that each fit a sheet and nested (docs/print.md,
/// "Fit layout"), or each part whole, tiled across sheets with overlap marks.
enum class PageLayoutMode { Fit, Tile };

std::string_view page_layout_name(PageLayoutMode mode);

struct PageOptions {
  Paper paper;
  double margin_mm = 10;   ///< unprinted border on each side
  double overlap_mm = 10;  ///< shared strip between neighbouring tiles

  /// \throw InvalidOptionException naming the bad option (by its JobOptions name).
  void validate() const;
};

/// One printed page: the window of the layout it shows.
struct Page {
  int row = 0, col = 0;  ///< row 0 is the top row
  Vec2 lo, hi;           ///< window in layout coordinates (mm, y up)
  /// The overview page (print/overview.h): a map of the other pages, no window of the layout
  /// (lo > hi, so it holds no point).
  bool overview = false;
};

struct Overview;

/// How a layout is split onto pages. All pages share one orientation.
struct PageLayout {
  double width = 0, height = 0;  ///< page size as printed (landscape when width > height)
  double margin = 0, overlap = 0;
  bool quarter_turn = false;  ///< the layout was turned by 90 degrees (see turn_quarter)
  /// Pages of a fit layout (print/nest.h): each a whole sheet, nothing shared between pages, so
  /// no overlap marks; false: tiles of one net.
  bool fitted = false;
  int rows = 1, cols = 1;
  std::vector<Page> pages;  ///< row by row, left to right; empty tiles left out
  /// With an overview page (add_overview, layout fit): what it shows.
  std::shared_ptr<const Overview> overview;
  /// The kit's name (the option `title`), printed on every page beside its number and as the
  /// overview's title; empty: none.
  std::string title;
};

/// Splits a layout onto pages, choosing orientation (page portrait or landscape, net turned or
/// not) to use the fewest pages; ties prefer portrait pages, then the net's long side along
/// the page's long side. Turns `layout` by a quarter when
/// that is the choice. A layout that fits one page is centred on it. Tiles of the rows x cols
/// grid that show nothing of the net (faces, tabs) are left out of `pages`, unless one is
/// needed to print a glue strip wholly (a strip that no printed tile holds wholly). Glue strips
/// that no tile showing the net holds wholly are first moved into free space on such a tile
/// where there is room (nearest their edge; same checks as place_strips).
/// \throw InvalidOptionException for invalid options (e.g. margins that leave no room).
PageLayout paginate(PrintLayout& layout, const PageOptions& options);

/// Turns a layout by 90 degrees counter-clockwise, keeping it in [0, size.x] x [0, size.y].
void turn_quarter(PrintLayout& layout);

/// Which drawing layer a shape belongs to (one SVG group or one PDF drawing pass each).
enum class Layer { Faces, Tabs, Strips, Cut, Mountain, Valley, Leaders, Labels, Marks };

/// A shape in page coordinates (mm, y down, origin at the page's top-left corner).
struct Shape {
  Layer layer = Layer::Cut;
  std::vector<Vec2> points;  ///< polyline, or polygon when closed; text: its centre only
  bool closed = false;
  std::string text;      ///< non-empty for text
  double size = 0;       ///< text height, mm
  double angle_deg = 0;  ///< text baseline, degrees clockwise on the page (SVG rotate())
  /// Text or a leader line drawn white, over a dark colour (docs/print.md, "Labels").
  bool light = false;
  /// A sample of its layer's line in the key of the page's top margin (docs/print.md, "The
  /// key"): drawn in that layer's style but outside the printable area, unclipped.
  bool key = false;
  /// Text that starts at `points[0]` (the middle of its left end), where other text is centred
  /// on it: the build order's lines, aligned in their columns.
  bool start = false;
};

/// Everything on one page, culled to the page's printable area (writers clip to `clip_*`).
struct PageDrawing {
  double width = 0, height = 0;
  Vec2 clip_lo, clip_hi;
  std::vector<Shape> shapes;
  std::vector<PageImage> images;  ///< the pieces' colour, under every layer but faces and tabs
  std::string title;  ///< the SVG's <title>: the page's line ("Duck · page 2 of 5"); empty: none
};

/// The shapes of page `index` of a paginated layout, with tile overlap marks, page number
/// ("page k of n", after the title where there is one: "Duck · page k of n") and, in the top margin
/// where it has room, the key to the lines (cut, mountain fold, valley fold); the overview page's
/// are draw_overview's (print/overview.h). With `colour`, the coloured pieces' images on it.
PageDrawing draw_page(const PrintLayout& layout, const PageLayout& pages, int index,
                      const PrintColour* colour = nullptr);

/// The whole layout as one drawing sized to the net plus `margin_mm` (no paper).
PageDrawing draw_unpaged(const PrintLayout& layout, double margin_mm,
                         const PrintColour* colour = nullptr);

}  // namespace papernet
