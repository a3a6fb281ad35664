#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/progress.h"
#include "core/tabs/tab_clearance_options.h"
#include "core/unfold/folds.h"
#include "core/unfold/net.h"
#include "core/unfold/net_metrics.h"
#include "print/fit_goal.h"
#include "print/labels.h"
#include "print/merge_budget.h"
#include "print/strips.h"
#include "print/tab_mode.h"
#include "print/tabs.h"

namespace papernet {

/// How a net is drawn on paper. Lengths are millimetres.
struct PrintOptions {
  double size_mm = 200;          ///< longest side of the model's bounding box, as folded
  double scale = 0;              ///< millimetres per model unit; > 0 overrides size_mm
  double flat_fold_degrees = 1;  ///< folds flatter than this are Flat
  bool draw_flat_folds = false;  ///< draw Flat folds (as mountain/valley by their sign)
  TabMode tabs = TabMode::Auto;
  double tab_height_mm = 6;  ///< tallest tab (and widest strip half); 0 means TabMode::None
  double tab_angle_deg = 45;
  /// Lowest tab printed (half the edge where that is less); edges without room for it get a
  /// glue strip.
  double min_tab_height_mm = 2;
  /// Candidate moves of the pass that changes the net before printing so that more cut edges
  /// have room for a tab (makes_tab_room), at most, in each of its two rounds
  /// (TabClearanceOptions::max_evaluations; 0: no pass). More opens more edges on dense meshes
  /// (docs/tabs.md has the cost of a move).
  std::size_t tab_room_budget = kDefaultTabRoomBudget;
  /// Clock limit of that pass in seconds (TabClearanceOptions::time_limit_seconds); <= 0: only
  /// its deterministic budget. The service sets it from the job's time limit.
  double tab_room_seconds = 0;
  /// Moved-face tests the merge of pieces after the fit search (layout fit) spends at most, with
  /// a sixth as many tab room evaluations (MergeBudget::of_tests; 0: no merge). More merges
  /// more pieces on some meshes, at seconds more (docs/print.md, "Pieces merged after the
  /// search").
  std::size_t merge_budget = kDefaultMergeBudget;
  /// What the fit layout saves first, sheets or pieces to cut out (FitGoal).
  FitGoal prefer = FitGoal::Sheets;
  bool labels = true;
  double max_label_mm = 4;  ///< label text height cap; labels shrink to fit their face
  /// Clock limit of the labels' placement in seconds (not counting the layout before it); <= 0
  /// or not finite: none. A label not yet moved where it prints at the legible size when it runs
  /// out keeps the size that fits its face. The fit search sets it for the chosen print's labels
  /// from what is left of its time (engine/fit_search.cpp).
  double label_seconds = 0;

  /// \throw InvalidOptionException naming the bad option (by its JobOptions name).
  void validate() const;
};

struct Segment {
  Vec2 a, b;
  int face = -1;  ///< the face whose side or tab it outlines (-1: none), so it moves with it
};

/// A net ready to draw: millimetres, y up, rotated into its minimum-area box, everything (faces,
/// tabs, strips) inside [0, size.x] x [0, size.y]. Every interior cut edge has exactly one tab
/// or one strip (unless TabMode::None), and none overlaps a face, a tab or a strip.
struct PrintLayout {
  double scale = 1;  ///< millimetres per model unit
  std::vector<std::array<Vec2, 3>> faces;
  std::vector<NetEdge> edges;
  std::vector<Segment> cut;       ///< cut edges without a tab, tab outlines, boundary edges
  std::vector<Segment> mountain;  ///< mountain folds and tab hinges (tabs fold backwards)
  std::vector<Segment> valley;
  std::vector<Tab> tabs;
  std::vector<GlueStrip> strips;  ///< separate glue strips, for cut edges without a tab
  std::vector<int> omitted_tabs;  ///< edges (indices into `edges`) with neither (TabMode::None)
  std::vector<Label> labels;
  /// Leader lines (docs/print.md, "Labels"): from a label that found no legible place at its
  /// edge, printed farther away on its piece, to a point of its edge (`face`: the label's).
  std::vector<Segment> leaders;
  /// With several pieces, each piece's number ("P3", from 1 in build order) inside one of its
  /// faces (`side.face`; `edge` -1), larger than the edge labels where the face holds it.
  std::vector<Label> piece_labels;
  Vec2 size;
  NetBoxMetrics metrics;  ///< of the net itself, in model units
  int cut_edges = 0;      ///< interior cut edges (label numbers run 1..cut_edges)
};

/// How large a layout's labels print: on faces and on glue strips.
struct LabelSizes {
  std::size_t count = 0;
  double smallest_mm = 0;     ///< 0 without labels
  std::size_t illegible = 0;  ///< under kLegibleLabelMm
};
LabelSizes label_sizes(const PrintLayout& layout);

/// Millimetres per model unit: `options.scale` when set, else `options.size_mm` over the
/// longest side of the mesh's bounding box (1 for a mesh without extent).
double print_scale(const Mesh& mesh, const PrintOptions& options);

/// The tab clearance options (core/tab_clearance.h) of a print: the lowest tab
/// (`min_tab_height_mm`, at most `tab_height_mm`) in model units at the print scale, the tabs'
/// slant, the budget and the clock limit of the pass.
TabClearanceOptions tab_clearance_options(const Mesh& mesh, const PrintOptions& options);

/// True when a net printed with `options` first gets room made for its glue tabs
/// (core/tabs/tab_clearance.h, with tab_clearance_options): tabs auto, tabs at all, a budget.
bool makes_tab_room(const PrintOptions& options);

/// Whether layout_net places the labels. Unplaced: each cut edge's labels keep their text, edge
/// and side but get no size or place, and there are no leaders or piece numbers; the faces, tabs
/// and glue strips are those of the same layout with its labels placed. For a layout that is
/// only weighed, not printed (the fit search's tries, when labels do not count:
/// engine/fit_search.cpp), which then skips most of its work on a dense net.
enum class LabelPass { Placed, Unplaced };

/// Lays out a net for printing. With `piece` (each face's piece, numbered in build order:
/// print/build_order.h), the two labels of a cut edge that joins two pieces also name the piece
/// across it ("12→P3": edge 12 glues to piece 3; docs/print.md, "Build order"), and each piece
/// of several gets its number (`piece_labels`). `large` (rooms in millimetres) names the faces
/// whose tabs hang from the faces beside them where they can (TabOptions::large).
/// \throw InvalidOptionException for invalid options; InvalidInputException for an empty mesh or
///        a net that does not match the mesh (sizes, non-finite points, vertex indices out of
///        range).
PrintLayout layout_net(const Mesh& mesh, const Net& net, const PrintOptions& options = {},
                       const std::vector<int>& piece = {}, const LargeFaces& large = {},
                       LabelPass label_pass = LabelPass::Placed);

}  // namespace papernet
