#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/progress.h"
#include "core/unfold/net.h"

namespace papernet {

/// Budget and randomness of a Tabu Unfolder run (docs/architecture.md, "The unfolder").
struct TabuOptions {
  std::uint64_t seed = 1;                   ///< every random choice derives from it
  std::size_t max_iterations = 10'000'000;  ///< moves (0: no limit)
  /// Faces moved and tested while evaluating candidate moves, at most (0: no limit): a
  /// deterministic measure of work (an evaluation costs the size of the side it moves).
  std::size_t max_tests = 0;
  double time_limit_seconds = 60;  ///< wall-clock budget (<= 0: no limit)
  std::string phase = "unfold";    ///< ProgressInfo::phase of the reports
  std::size_t input_faces = 0;     ///< ProgressInfo::input_faces (0: current faces)
  /// resolve_overlaps stops (returns false) when the fewest overlaps seen have not dropped for
  /// this many iterations (0: never); unfold_tabu then restarts from another start.
  std::size_t stall_iterations = 0;
  /// Walks per iteration at most, once stalled. The paper applies the best move of one walk; on
  /// CAD meshes with slivers that move is often a large step up and the count wanders on a
  /// plateau. So once the fewest overlaps seen have not dropped for |F| iterations, an iteration
  /// whose best move so far raises the count by more than `accept_rise` pairs tries another walk
  /// (new random overlapping face, new random root), up to `walks`, and applies the best move of
  /// all. Before that stall (and with walks = 1) it is the paper's rule. Measurements:
  /// docs/performance.md.
  std::size_t walks = 4;
  std::size_t accept_rise = 2;  ///< see `walks`
  /// Share of walks (a coin flip each, from the seed) that end at a face the start face overlaps
  /// instead of at a random root, so that every cut on the walk separates an overlapping pair
  /// and the walk is as short as the tree path between them. The paper's walks go to a random
  /// root (0 restores that exactly); on CAD meshes of slivers their cuts are mostly far from the
  /// overlap and move large sides, and the count stalls (docs/performance.md).
  double partner_walks = 0.5;
};

/// What one Tabu Unfolder run did.
struct TabuStats {
  std::size_t iterations = 0;   ///< rounds (a random overlapping face each)
  std::size_t evaluations = 0;  ///< candidate moves evaluated
  std::size_t tests = 0;        ///< faces moved and tested by those evaluations
  double seconds = 0;
  /// Adds another run's work (iterations, evaluations, tests; not its seconds).
  void add(const TabuStats& run) {
    iterations += run.iterations;
    evaluations += run.evaluations;
    tests += run.tests;
  }
};

/// Result of an unfolding strategy.
struct UnfoldResult {
  Net net;
  bool overlap_free = false;
  std::size_t overlaps = 0;
  TabuStats stats;
};

/// Plain Tabu Unfolding (strategy `TU`): starts from the steepest-edge tree of `options.seed` or
/// the minimum-perimeter tree, whichever has fewer overlapping pairs, then resolve_overlaps. When
/// the overlap count stalls (no new minimum for a number of iterations that grows with the mesh and
/// with each restart) the walk restarts from the steepest-edge tree of another direction derived
/// from the seed, within the same budget; the result is the state with the fewest overlaps seen at
/// the end of an attempt. Deterministic for a seed (up to the time limit). The net is of `mesh`
/// itself. \throw InvalidInputException when the mesh cannot be unfolded as one piece, and when its
/// dual graph is a tree (a single edge unfolding exists) whose unfolding overlaps, at once.
UnfoldResult unfold_tabu(const Mesh& mesh, const TabuOptions& options, Progress& progress);

/// unfold_tabu with one more attempt before its own: from the unfold tree `parent` of `mesh` (the
/// face each face hangs from, -1 for the root), such as a tree that progressive unfolding nearly
/// finished, until it stalls for max(10,000, 5 per face) iterations or has made 15,000 moved-face
/// tests per face; then unfold_tabu's attempts
/// within what is left of the budget. \throw TopologyException when `parent` is not a spanning tree
/// of adjacent faces, and as unfold_tabu.
UnfoldResult unfold_tabu_from(const Mesh& mesh, const std::vector<int>& parent,
                              const TabuOptions& options, Progress& progress);

}  // namespace papernet
