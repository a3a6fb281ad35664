// Private to engine/: the fit search (engine/fit_search.cpp; docs/print.md, "Fit layout"), the
// print's first step with layout fit: ways of making pieces that fit a sheet tried in turn, the
// cheapest print kept and its pieces merged.
#pragma once

#include <optional>
#include <string>

#include "api/net_json.h"
#include "api/options.h"
#include "core/mesh/mesh.h"
#include "core/progress.h"
#include "core/tabs/tab_clearance_options.h"
#include "print/build_order.h"
#include "print/fit.h"
#include "print/fit_goal.h"
#include "print/layout.h"
#include "print/pages.h"

namespace papernet::engine_detail {

/// Paper left between nested pieces (with their tabs) on a sheet, to cut along.
constexpr double kCutSpacingMm = 2;

/// Tendrils cut off the chosen print's pieces to save a sheet, at most: a sheet is worth 20
/// pieces (kPiecesPerSheet), but more pieces are more to cut out and glue, and 5 save most of
/// the sheets that 10 do (docs/print.md, "Tendrils cut off to save a sheet").
constexpr int kTendrilCuts = 5;

/// The net cut into pieces, numbered in build order, laid out and nested onto sheets.
struct FitPrint {
  FitPieces pieces;
  PieceGraph graph;
  PrintLayout layout;
  PageLayout pages;

  /// Pieces and glue strips to cut out, and at `label_price` pieces each labels under the
  /// legible size, against sheets: with FitGoal::Sheets, in sheets, the rest at kPiecesPerSheet
  /// to a sheet; with FitGoal::Pieces, in pieces, each sheet worth 1 / kPiecesPerSheet of a
  /// piece.
  double cost(double label_price, FitGoal goal) const;
  /// Whether no print can cost less: it is on one sheet (Sheets: no sheet left to save, as
  /// pieces count for less), and one piece for each of the model's `parts` without a glue strip
  /// (Pieces: nothing left to save at all).
  bool nothing_to_save(FitGoal goal, int parts) const;
};

/// What the fit search works with.
struct FitSearchOptions {
  PrintOptions print;
  PageOptions page;
  TabClearanceOptions tabs;  ///< the room made for tabs on the pieces merged
  double scale = 1;          ///< millimetres per model unit
  double gap = 0;            ///< between pieces set side by side, in model units
  double model_mm = 0;       ///< the model's longest side as printed
  /// Whether labels under the legible size count in a print's cost (detail=auto: the detail was
  /// chosen for legible labels).
  bool labels_count = false;
  FitRoom room;
  double seconds = 0;  ///< the search's time: the ways after the first start while it lasts
  /// Whether a face too large for the paper tiles the print instead of failing (the layout was
  /// not asked for).
  bool may_tile = false;
  int threads = 1;  ///< ways laid out at a time
  /// Tendrils cut off the chosen print's pieces to save a sheet, at most (docs/print.md,
  /// "Tendrils cut off to save a sheet"; 0: none).
  int tendril_cuts = kTendrilCuts;
};

/// The search's options for printing `mesh` with `options` on paper, but its time and threads
/// (FitSearchOptions::seconds, threads).
/// \throw InvalidOptionException for paper that the margins and tabs leave no room on.
FitSearchOptions fit_search_options(const JobOptions& options, const Mesh& mesh);

/// The search's choice: the cheapest print, or none when a face is too large for the paper and
/// the print may tile (`tiled_because` says why).
struct FitChoice {
  std::optional<FitPrint> print;
  std::string tiled_because;
};

/// The fit search over the net of `net` (whose mesh is `mesh`): the ways in turn, `threads` at a
/// time, while `seconds` last (at least the first); the cheapest print is kept, then its pieces
/// merged while that saves (docs/print.md, "Fit layout", "Pieces merged after the search"), and
/// its labels placed. Reports phase "layout" to `progress`.
/// \throw CancelledException; InvalidOptionException for a face too large for the paper when
///        the print may not tile.
FitChoice search_fit(const NetDocument& net, const Mesh& mesh, const FitSearchOptions& options,
                     Progress& progress);

}  // namespace papernet::engine_detail
