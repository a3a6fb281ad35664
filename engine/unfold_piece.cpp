// The pipeline's middle steps for one part: unfold it by the job's strategy, then make room for
// glue tabs on its net.
#include <algorithm>
#include <chrono>
#include <numbers>
#include <utility>

#include "core/errors.h"
#include "core/mesh/dual_graph.h"
#include "core/mesh/hausdorff.h"
#include "core/mesh/simplify.h"
#include "core/tabs/tab_clearance.h"
#include "core/tabs/tab_clearance_report.h"
#include "core/unfold/progressive.h"
#include "core/unfold/tabu.h"
#include "engine/internal/steps.h"
#include "print/fit.h"
#include "print/grow.h"
#include "print/layout.h"

namespace papernet::engine_detail {
namespace {

// The share of a part's seconds the steps of detail auto for short edges may take (simplify_mesh).
constexpr double kSimplifyShare = 0.5;

// Where detail auto collapsed a part, AUTO's complete-first run on the collapsed mesh (when the
// uncollapse stops short of it) takes at most this many seconds, and this many more per face:
// the net is approximate either way, and a collapsed mesh that the uncollapse cannot finish
// rarely yields to more (thingi10k 55581, 264 faces collapsed to 69: 52 s of the 60 s limit for
// the same approximate net the first 2.6 s gave).
constexpr double kCollapsedFinishSeconds = 2;
constexpr double kCollapsedFinishSecondsPerFace = 0.005;

// AUTO's growths of a step of splits whose Tabu run is stuck (ProgressiveOptions::
// stuck_step_growths): up to 4 x 2^8 = 1,024 splits applied again at once. c3d__beetle-alt
// (38,656 faces), whose uncollapse had stopped at 757 faces for every seed, needed 512 there
// and 1,024 at 2,223 faces (docs/performance.md, "Session 62").
constexpr std::size_t kStuckStepGrowths = 8;
// ProgressiveOptions::walk_after_restarts of the default strategy (docs/performance.md,
// "Session 63"); also where detail collapsed the part, unlike growths: walks come only after
// restarts, which need 4,000 faces (ProgressiveOptions::restart_faces), and the parts it collapses
// at the usual sizes have fewer (the chair above: 429).
constexpr std::size_t kWalkAfterRestarts = 8;

// The tab room report's threshold for a flat vertex (angle defect); only its flat-leaf counts
// depend on it, and those are not reported.
constexpr double kFlatDefect = 10 * std::numbers::pi / 180;

// The collapses of a progressive strategy (AUTO's are QQ's), and those that simplify uses for TU.
CollapseStrategy collapses_of(Strategy strategy) {
  switch (strategy) {
    case Strategy::SEMP:
      return CollapseStrategy::SEMP;
    case Strategy::SEQ:
      return CollapseStrategy::SEQ;
    case Strategy::QQ:
    case Strategy::TU:
    case Strategy::AUTO:
      break;
  }
  return CollapseStrategy::QQ;
}

// Pieces of `mesh` grown from single faces (grow_to_fit, with no sheet to fit: as large as they
// lie flat), for a mesh the unfolder found no single-piece net of, whose best had `overlaps` left.
// When the job prints tabs, a join that leaves a cut inside a piece without room for a tab is
// refused: the pass that makes room for tabs works on one tree, and does not run on these.
Piece grow_pieces(const Mesh& mesh, const JobOptions& options, std::size_t overlaps,
                  std::size_t iterations) {
  const PrintOptions print = print_options(options);
  const TabClearanceOptions tabs = tab_clearance_options(mesh, print);
  constexpr double kNoSheet = 1e300;
  FitPieces grown = grow_to_fit(mesh, std::vector<int>(mesh.faces.size(), 0), 1,
                                FitRoom{{kNoSheet, kNoSheet}, {}},
                                makes_tab_room(print) ? tabs.min_height : 0, tabs.angle_deg);
  return {mesh,
          std::move(grown.net),
          true,
          false,
          0,
          iterations,
          GrownPieces{std::move(grown.piece), static_cast<std::size_t>(grown.pieces), overlaps,
                      build_dual_graph(mesh).is_tree()}};
}

// `collapsed`: `mesh` is the part collapsed by detail (kCollapsedFinishSeconds).
Piece unfold_mesh(const Mesh& mesh, const JobOptions& options, double seconds,
                  const AfterUnfold& after, std::size_t input_faces, bool collapsed,
                  Progress& progress) {
  TabuOptions tabu;
  tabu.seed = options.seed;
  tabu.time_limit_seconds = seconds;
  tabu.input_faces = input_faces;
  if (options.strategy == Strategy::TU) {
    // Every face is in the net: the steps after it need their time for all of them.
    const double kept = after.per_face * static_cast<double>(mesh.faces.size()) - after.reserved;
    tabu.time_limit_seconds = std::max(kLeastSeconds, seconds - std::max(0.0, kept));
    UnfoldResult r;
    try {
      r = unfold_tabu(mesh, tabu, progress);
    } catch (const InvalidInputException&) {
      // Its dual graph is a tree and its one edge unfolding overlaps: no net in one piece at all,
      // as the progressive strategies find when they unfold the whole part.
      if (!build_dual_graph(mesh).is_tree()) throw;
      return grow_pieces(mesh, options, 0, 0);
    }
    if (!r.overlap_free) return grow_pieces(mesh, options, r.overlaps, r.stats.iterations);
    return {mesh, std::move(r.net), true, false, 0, r.stats.iterations, {}};
  }
  ProgressiveOptions p;
  p.strategy = collapses_of(options.strategy);
  p.target_faces = options.target_faces.value_or(0);
  p.tabu = tabu;
  p.complete_first = options.strategy == Strategy::AUTO;
  // Not where detail collapsed the part: the net is approximate either way, and the complete-first
  // run finishes the collapsed mesh (the chair of tests/engine/fit_search_test.cpp, 429 faces of
  // 6,374: grown, its net printed on 22 pieces with 11 labels under 1.5 mm instead of 19 and 8).
  if (options.strategy == Strategy::AUTO && !collapsed) p.stuck_step_growths = kStuckStepGrowths;
  if (options.strategy == Strategy::AUTO) p.walk_after_restarts = kWalkAfterRestarts;
  if (collapsed)
    p.complete_first_seconds = kCollapsedFinishSeconds + kCollapsedFinishSecondsPerFace *
                                                             static_cast<double>(mesh.faces.size());
  p.after_seconds_per_face = after.per_face;
  p.after_seconds_reserved = after.reserved;
  ProgressiveResult r = unfold_progressive(mesh, p, progress);
  if (!r.overlap_free) return grow_pieces(mesh, options, r.overlaps, r.stats.iterations);
  return {std::move(r.mesh), std::move(r.net),   r.complete, false,
          r.hausdorff,       r.stats.iterations, {}};
}

}  // namespace

Piece unfold_piece(const Mesh& part, const JobOptions& options, const SimplifyTarget& detail,
                   double seconds, const AfterUnfold& after, std::size_t input_faces,
                   Progress& progress) {
  // A low-poly version to print instead of the part, when asked for: the net is then
  // approximate, its distance measured to the part. Its time comes out of the part's: at most
  // half of it for the steps for short edges.
  const auto start = std::chrono::steady_clock::now();
  SimplifyTarget limited = detail;
  limited.seconds = kSimplifyShare * seconds;
  std::optional<Mesh> simple =
      simplify_mesh(part, collapses_of(options.strategy), limited, progress);
  const double left = std::max(
      kLeastSeconds,
      seconds - std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  if (!simple) return unfold_mesh(part, options, left, after, input_faces, false, progress);
  Piece piece = unfold_mesh(*simple, options, left, after, input_faces, true, progress);
  piece.simplified = true;
  piece.complete = false;
  piece.hausdorff = approximation_distance(part, piece.mesh);
  return piece;
}

NetCheckReport check_piece(const Piece& piece) {
  return piece.grown ? check_pieces(piece.mesh, piece.net, piece.grown->piece)
                     : check_net(piece.mesh, piece.net);
}

NetCheckReport make_room_for_tabs(Piece& piece, const JobOptions& options, double seconds,
                                  double seconds_per_strip, Progress& progress,
                                  std::optional<TabRoomSummary>& summary) {
  PrintOptions print = print_options(options);
  if (!makes_tab_room(print)) return check_piece(piece);
  print.tab_room_seconds = seconds;
  TabClearanceOptions clearance = tab_clearance_options(piece.mesh, print);
  clearance.seconds_per_blocked_edge = seconds_per_strip;
  const auto start = std::chrono::steady_clock::now();
  const TabClearanceResult room = clear_tab_room(piece.mesh, piece.net, clearance, progress);
  TabRoomSummary& s = summary ? *summary : summary.emplace();
  s.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  s.blocked_before += room.blocked_before;
  s.moves += room.moves;
  s.kicks += room.kicks;
  s.evaluations += room.evaluations;
  std::optional<NetCheckReport> report;
  std::size_t blocked = room.blocked_after;
  bool rejected = false;  // the pass's net fails the check: the piece keeps its own
  if (room.moves > 0) {
    report = check_net(piece.mesh, room.net);
    if (report->ok()) {
      piece.net = room.net;
    } else {
      s.rejected = rejected = true;
      blocked = room.blocked_before;
      report.reset();
    }
  }
  s.blocked_after += blocked;
  if (blocked > 0) {
    // Why edges stay without room: a leaf of the cut tree at a nearly flat vertex always lacks
    // it, and a dense mesh has few vertices where a leaf can have it.
    // The pass's own list when its net is the piece's.
    const std::vector<EdgeSide>* known = !rejected && room.blocked ? &*room.blocked : nullptr;
    const TabRoomReport why =
        describe_tab_room(piece.mesh, piece.net, clearance, kFlatDefect, known);
    s.leaves_without_room += why.leaves_without_room_blocked;
    s.leaf_room_vertices += why.leaf_room_vertices;
    s.interior_vertices += why.interior_vertices;
  }
  return report ? std::move(*report) : check_net(piece.mesh, piece.net);
}

}  // namespace papernet::engine_detail
