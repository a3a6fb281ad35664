#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "core/mesh/decimate.h"
#include "core/mesh/mesh.h"
#include "core/progress.h"
#include "core/unfold/net.h"
#include "core/unfold/unfolding.h"

namespace papernet {

struct ProgressiveOptions {
  CollapseStrategy strategy = CollapseStrategy::QQ;
  /// Face count of the coarse mesh; 0 means the paper's t_f (see collapse_target).
  std::size_t target_faces = 0;
  /// Seed of every random choice, the whole run's time limit, and the iteration limit of each
  /// Tabu Unfolder run (on the coarse mesh and after each split that creates overlaps).
  TabuOptions tabu;
  /// Time limit of the Tabu Unfolder after one split (the whole run's limit applies too); when
  /// a split's overlaps cannot be removed within it, the result is approximate.
  double split_time_limit_seconds = 10;
  /// Iteration limit of the Tabu Unfolder after one split; 0 means automatic: the larger of
  /// 2,000 + 5 per face of the current mesh and all Tabu iterations before that split (capped by
  /// tabu.max_iterations).
  std::size_t split_iterations = 0;
  /// Work budget of the Tabu Unfolder over all splits, in faces moved and tested while evaluating
  /// candidate moves (TabuStats::tests), per input face (at least 2,000 faces, and times the
  /// input's faces over 2,000 beyond: a move's tests grow with the mesh; 0: none). Most
  /// splits need none (the local repair clears their overlaps); a mesh whose splits keep needing
  /// long Tabu runs (CAD parts with slivers) ends as an approximation once the budget is spent,
  /// instead of taking up to the whole time limit. Deterministic.
  std::size_t split_tests_per_face = 1250;
  /// Restarts of a long Tabu run after a split, on meshes of at least `restart_faces` faces (0:
  /// never): a run that has not removed the split's overlaps within its cap of moved-face tests
  /// goes back to where it started and searches again with another seed. The caps follow the
  /// Luby sequence (1 1 2 1 1 2 4 1 ...) in units of `restart_tests_per_face` per face of the
  /// current mesh, until a run succeeds, a run ends by another limit (its iterations, time, the
  /// split budget; then the result is approximate) or a cap would exceed what is left of the
  /// split budget (then a last run gets all of it). These runs are heavy-tailed on large meshes
  /// (docs/performance.md, "Session 37" and "Session 60"). Deterministic.
  std::size_t restart_faces = 4000;
  std::size_t restart_tests_per_face = 8;
  /// Growths of a stuck step (0: none; the default strategy uses them, docs/performance.md): when
  /// the Tabu run after a step of splits ends by its iteration cap, the mesh at that level may
  /// have no net near them (c3d__beetle-alt at 763 faces, every seed: a vertex whose angles sum
  /// past 360 degrees, whose six faces reach the rest of the mesh across two edges only, and the
  /// tree cut one edge of its fan, which then overlapped itself). The state goes back to before
  /// the step, which is applied again with twice as many splits (the next in the order) until a
  /// run separates them or this many growths failed. A growth's run gets (2,000 + 5 per face)
  /// times 2^(growth / 2) iterations (rounded down), unless split_iterations fixes them.
  /// Deterministic.
  std::size_t stuck_step_growths = 0;
  /// Walks after restarts (0: none; the default strategy uses them, docs/performance.md): from
  /// this many failed capped Tabu runs of a step on, each failed run is followed by a walk of
  /// local moves from the same state (Unfolding::repair_locally with a seed: sideways moves
  /// drawn, not the best ones), within the same cap of moved-face tests and at most the local
  /// repair's budget after a split (it checks neither time nor cancellation). The few updates that
  /// take most of a large mesh's minute have one or two pairs left that a Tabu run separates in
  /// about one try of a hundred; most walks end within a few thousand tests, and in one minute
  /// of c3d__nefertiti 13 of 295 separated such pairs. Deterministic.
  std::size_t walk_after_restarts = 0;
  /// Vertex splits applied together before one re-layout (Unfolding::update) and repair; 0 means
  /// automatic: four, and one per 4,000 faces of the current mesh beyond 16,000. Together, the
  /// tree parts that several splits move are re-laid out and tested once (docs/performance.md).
  std::size_t splits_per_update = 0;
  /// Iteration limit of the Tabu Unfolder on a coarse mesh that may still be collapsed further
  /// when it fails; 0 means automatic (iterations and moved-face tests growing with its face
  /// count, ended early by a stall: work, not time, so that load does not change the net).
  std::size_t coarse_iterations = 0;
  /// Complete first (the default strategy, docs/performance.md): when the uncollapse stops short
  /// of the input (a split whose overlaps stay within the budgets above), keep its last
  /// overlap-free state as the fallback and spend what is left of the time limit on the input
  /// itself: the Tabu Unfolder from the tree the uncollapse stopped with, every remaining split
  /// applied to it (unfold_tabu_from, with its restarts). The result is approximate only when
  /// that finds no net either.
  bool complete_first = false;
  /// Seconds complete_first's run on the input may take at most (0: what is left of the time
  /// limit). The pipeline caps it where the input is itself an approximation (detail auto).
  double complete_first_seconds = 0;
  /// Seconds per face of the net that the steps after the uncollapse take (the caller's print and
  /// glue tabs, the distance of an approximate net to the input), of which
  /// `after_seconds_reserved` are already outside tabu.time_limit_seconds. Under a time limit the
  /// uncollapse stops, and the complete-first run on the input does not start, when the time
  /// left would not cover the rest for the faces the net has (or would have). 0: none.
  double after_seconds_per_face = 0;
  double after_seconds_reserved = 0;
};

/// Outcome of progressive unfolding.
struct ProgressiveResult {
  /// The net folds into the input itself; `mesh` is the input and `face_ids` the identity.
  bool complete = false;
  /// `net` has no overlapping faces. False only when not even the coarse mesh could be unfolded
  /// within the budget (then `net` is the coarse mesh's best attempt).
  bool overlap_free = false;
  Mesh mesh;                  ///< the mesh that `net` folds into
  Net net;                    ///< net.points[i] belongs to mesh.faces[i]
  std::vector<int> face_ids;  ///< input face id of each face of `mesh`
  /// Two-sided Hausdorff distance of `mesh` to the input relative to the input's bounding-box
  /// diagonal (0 when complete).
  double hausdorff = 0;
  std::size_t overlaps = 0;        ///< overlapping pairs left in `net`
  std::size_t coarse_faces = 0;    ///< faces of the coarse mesh that was unfolded
  std::size_t coarse_retries = 0;  ///< further collapses after a coarse mesh failed
  std::size_t splits = 0;          ///< vertex splits the net includes
  std::size_t splits_total = 0;    ///< collapses made
  /// Passes of going back to the last checkpoint and replaying the splits after it: one for each
  /// growth of a stuck step, and one when the uncollapse stops with a split's overlaps left (a
  /// replay that diverged from the run it repeats would need more and lose splits).
  std::size_t replays = 0;
  std::size_t restarts = 0;  ///< Tabu runs after splits that started again (see the options)
  std::size_t growths = 0;   ///< stuck steps applied again with more splits (see the options)
  std::size_t walks = 0;     ///< steps whose pairs a walk after restarts separated (the options)
  /// complete_first gave the net: the uncollapse stopped, the Tabu Unfolder finished the input.
  bool continued = false;
  TabuStats stats;  ///< Tabu Unfolder work summed over all runs
  double seconds = 0;
};

/// Progressive Mesh Unfolding (the paper's Algorithm 1, docs/architecture.md): collapse the
/// mesh with `options.strategy`, unfold the coarse mesh (steepest edge, then the Tabu Unfolder),
/// then undo the collapses a few vertex splits at a time (`splits_per_update`), inserting each
/// new face into the unfold tree between the two faces linked across its wing (else as a leaf
/// of a random neighbour), re-laying out and testing only what moved, repairing new overlaps by
/// local moves (Unfolding::repair_locally) and running the Tabu Unfolder only when those leave
/// some. When that fails within the budget (the time limit, `split_tests_per_face`, or a split
/// whose overlaps need more Tabu iterations than everything before it and than 2,000 + 5 per
/// face, after `stuck_step_growths` growths of the step), the last overlap-free state is
/// returned (`complete` false), unless `complete_first` finishes the input from there.
///
/// When the coarse mesh itself cannot be unfolded within a budget that grows with its size (or,
/// when it may still be collapsed, starts with more than 10 overlapping pairs per face):
/// first, if the input's own steepest-edge or minimum-perimeter tree is already overlap-free,
/// that net is returned (complete); else the coarse mesh is collapsed further (half the faces
/// each time) and unfolded again, so that meshes too detailed for their shape still give an
/// approximate net (a retry starts from the minimum-perimeter tree when it has fewer overlaps
/// than the steepest-edge one). When no coarse mesh can be unfolded, plain Tabu Unfolding
/// (unfold_tabu) of the input gets what is left of the budget (the last coarse attempt gets half
/// of it) and gives a complete net when it finds one.
///
/// Progress: phases "collapse", "unfold", "uncollapse" in that order, faces never decreasing
/// during "uncollapse" (complete_first's Tabu run reports the input's), the last report at the
/// face count of the returned mesh; `intermediate`
/// receives overlap-free nets of coarser meshes now and then (at most every ~100 ms).
/// \throw InvalidInputException when the mesh is not a manifold, oriented triangle mesh.
/// \throw CancelledException when `progress` asks to stop.
ProgressiveResult unfold_progressive(const Mesh& mesh, const ProgressiveOptions& options,
                                     Progress& progress);

}  // namespace papernet
