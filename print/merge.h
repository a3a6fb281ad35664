#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "core/progress.h"
#include "core/tabs/tab_clearance_options.h"
#include "core/unfold/net.h"
#include "print/fit.h"
#include "print/merge_budget.h"

// The merge after the fit search: pieces joined two at a time, within a budget of work
// (docs/print.md, "Pieces merged after the search").

namespace papernet {

/// How much work merge_pieces may do: the Tabu Unfolder's moved-face tests, the tab room pass's
/// evaluations and the merges offered (work, not time: the same pieces on every run), and, where
/// a job's time limit bounds the print, seconds.
struct MergeBudget {
  /// The budget of `tests` tests in all, with a sixth as many tab evaluations (the defaults'
  /// share) and the other bounds at their defaults.
  static MergeBudget of_tests(std::size_t tests) {
    MergeBudget budget;
    budget.tests = tests;
    budget.tab_evaluations = tests / 6;
    return budget;
  }

  /// Unfoldings of a pair from its two pieces' trees glued across one of the edges they share
  /// (edges spread over those they share), before the `tries`.
  int glued = 2;
  int tries = 2;  ///< unfoldings of a pair from the Tabu Unfolder's starts, seeds 1, 2, ...
  std::size_t tests_per_face = 200;         ///< of one unfolding, per face of the pair
  std::size_t iterations_per_face = 20;     ///< rounds of one unfolding, per face of the pair
  std::size_t tests = kDefaultMergeBudget;  ///< of all unfoldings
  /// Candidate moves of the pass that makes room for tabs on a merged piece, per face of it.
  std::size_t tab_evaluations_per_face = 20;
  std::size_t tab_evaluations = kDefaultMergeBudget / 6;  ///< of all those passes
  /// Branches hung elsewhere to make an unfolding that lies flat but does not fit the room fit
  /// it, per face of the pair (print/internal/compact.h; 0: none).
  std::size_t compact_evaluations_per_face = 40;
  /// When no pair merges, a piece split between two of its neighbours (one piece fewer): the
  /// shares of its faces that go to the first, tried in turn until a split unfolds (none: no
  /// splits; three shares, 0.5, 0.25 and 0.75, left as many pieces as one, more slowly:
  /// docs/print.md, "Pieces merged after the search").
  std::vector<double> split_shares{0.5};
  std::size_t split_tests_per_face = 50;  ///< of one unfolding of a side of a split
  /// Merges offered to merge_pieces' `keep`, kept or not.
  std::size_t keeps = 64;
  /// Seconds for the whole merge (0: no bound; the work bounds alone give the same pieces on
  /// every run).
  double seconds = 0;
};

/// `pieces` (of `mesh`, each face's piece in `pieces.piece`, each a tree of `pieces.net`) merged
/// two at a time (docs/print.md, "Fit layout"): two pieces of one part (values of `part`) that
/// share an edge become one when their faces, unfolded anew together by the Tabu Unfolder (from
/// the two pieces' trees glued across a shared edge, `budget.glued` edges, then from its own starts
/// of seeds 1 to `budget.tries`), lie flat without overlap, fit `room` at `scale` millimetres per
/// unit as cut_to_fit's pieces do, and, with `tabs.min_height` > 0, leave room for a tab on every
/// cut inside the piece (core/tabs' edges_without_tab_room). The pairs of the fewest faces are
/// tried first, again after each merge. When no pair merges, a piece is split between two of its
/// neighbours (`budget.split_shares`, the smallest pieces first): its faces nearest the one join
/// it, the rest the other, each side unfolded anew from its piece's tree with the faces it takes
/// hanging towards it, and made when both lie flat and fit as a merged pair must. A piece of a
/// face larger than the room (`pieces.large`) stays as it is. With `keep`, each merge is offered to
/// it (at most `budget.keeps`) and made only when it says yes (the fit search keeps a merge that
/// prints on as many sheets or fewer at a lower cost); a pair refused is not tried again while
/// neither piece changes. With `keep` and `threads` > 1, the pairs after one offered are unfolded
/// on another thread while `keep` runs (one thread more, no more: the offers and pieces are those
/// of one thread; an unfolding made ahead is made again where the budget left has shrunk below
/// what it spent). Deterministic, unless `budget.seconds` stops it. With `progress`, reports
/// phase "merge" after each unfolding and each merge offered, its `phase_fraction` the share used
/// of the budget nearest its end (never decreasing), and throws CancelledException when it is
/// cancelled.
FitPieces merge_pieces(const Mesh& mesh, const std::vector<int>& part, FitPieces pieces,
                       double scale, FitRoom room, const TabClearanceOptions& tabs,
                       const MergeBudget& budget = {},
                       const std::function<bool(const FitPieces&)>& keep = {},
                       Progress* progress = nullptr, int threads = 1);

}  // namespace papernet
