#pragma once

#include <cstddef>

namespace papernet {

/// The options of the tab clearance pass (core/tabs/tab_clearance.h, clear_tab_room), in a header
/// of their own: the print's options hold them, and most of the print needs nothing else of the
/// pass.
struct TabClearanceOptions {
  /// Lowest tab worth printing, in model units (print: millimetres / scale); on an edge shorter
  /// than twice this, half the edge. <= 0: every edge has room, nothing to do.
  double min_height = 0;
  double angle_deg = 45;  ///< slant of a tab's sides, as the print layout's
  /// Candidate moves evaluated at most by the tabu search, and as many again by its second
  /// round (`second_round`): a deterministic budget (no clock), so the same net and options
  /// always give the same result. Both rounds also stop earlier when they no longer find better
  /// nets.
  std::size_t max_evaluations = 100'000;
  /// A clock limit in seconds besides the budget, for callers with a deadline (the service's
  /// job time limit); <= 0: none. When it stops the search, the best net so far is returned
  /// (overlap-free as always), and the result then depends on the machine's speed.
  double time_limit_seconds = 0;
  /// With a clock limit: the seconds the caller's next steps take for each edge still without
  /// room (the print nests a glue strip for each, docs/architecture.md "Time limit"). The
  /// search stops this much per edge before its limit, so it stops earlier on a net with many
  /// such edges, and later as it opens them.
  double seconds_per_blocked_edge = 0;
  /// Refuse moves that take faces outside the input net's axis-aligned bounding box, so that
  /// the net does not grow while it makes room for tabs. Off by default: it leaves about a
  /// quarter more edges without room and does not bound the page count anyway (pages follow
  /// the net's minimum-area rotated box; docs/tabs.md).
  bool keep_bounds = false;
  /// Also try compound moves (two edge swaps checked together, see clear_tab_room) where no
  /// single swap helps. On by default; off gives the search of single swaps only.
  bool compound_moves = true;
  /// A second round of `max_evaluations` after the tabu search (see clear_tab_room): more of
  /// the search when it spent its budget with many edges left, else kicks. On by default (not with
  /// keep_bounds, which kicks do not keep); off gives the tabu search alone.
  bool second_round = true;
};

}  // namespace papernet
