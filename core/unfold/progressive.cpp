#include "core/unfold/progressive.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <optional>
#include <utility>

#include "core/errors.h"
#include "core/mesh/hausdorff.h"
#include "core/mesh/progressive_mesh.h"
#include "core/unfold/internal/progressive_state.h"

namespace papernet {
namespace {

using progressive_detail::finish_on_input;
using progressive_detail::make_state;
using progressive_detail::net_in_input_ids;
using progressive_detail::place_splits;
using progressive_detail::repair_tests;
using progressive_detail::split_seed;
using progressive_detail::start_tree_net;
using progressive_detail::State;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Passes the Tabu Unfolder's reports on with the run's phase, face counts and elapsed time.
class Relay : public Progress {
 public:
  Relay(Progress& outer, Clock::time_point start) : outer_(outer), start_(start) {}
  ProgressInfo context;
  bool quiet = false;
  void report(const ProgressInfo& in) override {
    if (quiet) return;
    ProgressInfo out = context;
    out.overlaps = in.overlaps;
    out.iterations = in.iterations;
    out.elapsed_seconds = seconds_since(start_);
    outer_.report(out);
  }
  void intermediate(const Mesh& mesh, const Net& net) override { outer_.intermediate(mesh, net); }
  bool cancelled() override { return outer_.cancelled(); }

 private:
  Progress& outer_;
  Clock::time_point start_;
};

// A split that was applied, with what its Tabu run needed (to replay it exactly).
struct Applied {
  std::vector<VertexSplit> splits;  // one, or a batch on large meshes
  std::uint64_t seed = 0;           // of the new faces' places in the tree
  std::uint64_t tabu_seed = 0;      // of the Tabu run that removed their overlaps (after restarts)
  std::size_t iterations = 0;       // of that run; 0: no overlaps appeared
  // A walk after restarts that separated the pairs instead (ProgressiveOptions::
  // walk_after_restarts): its seed (0: none) and cap of tests.
  std::uint64_t walk_seed = 0;
  std::size_t walk_tests = 0;
};

// The walk of local moves that ProgressiveOptions::walk_after_restarts tries, also in replays.
LocalRepairOptions walk_options(const Unfolding& u, std::uint64_t seed, std::size_t tests) {
  LocalRepairOptions walk;
  walk.max_side = u.face_count();
  walk.max_tests = tests;
  walk.max_sideways = tests;  // bounded by the tests
  walk.seed = seed;
  return walk;
}

// Splits per update(): kSplitsPerUpdate, or one per kBatchFaces faces of the current mesh when
// that is more. Consecutive splits often move the same parts of the tree (the branches that meet
// their rings); together these are re-laid out and tested once. With eight per update the Tabu
// runs after splits grew (more new overlaps at once) and ate the gain (2,000 faces, seeds 1-3).
constexpr std::size_t kSplitsPerUpdate = 4;
constexpr std::size_t kBatchFaces = 4000;

// Tabu budget of a coarse attempt that may still be retried on a coarser mesh: iterations
// growing with the face count, an end when the fewest overlaps seen stall, and work (moved-face
// tests, TabuStats::tests) of kCoarseTestsPerFace per face, at least kCoarseTestsMin. Work, not
// time, so that the same seed gives the same net whatever the machine's load. It replaced a cap
// of 5e-4 s per face (at least 0.25 s) at 1.4 million tests a second, the middle of what the
// CAD attempts of bench/2000 that this cap ends do on an idle machine: 0.5-0.6 million on
// trimesh__1002_tray_bottom's first attempt, whose tests meet many large faces in the grid,
// 1.1-2.4 million on the others (up to 4 million on attempts that succeed).
constexpr std::size_t kCoarseIterationsBase = 2000;
constexpr std::size_t kCoarseIterationsPerFace = 20;
constexpr std::size_t kCoarseStallBase = 2000;
constexpr std::size_t kCoarseTestsMin = 350'000;
constexpr std::size_t kCoarseTestsPerFace = 700;
// Checkpoints of the uncollapse under a time limit: a twentieth of it apart, within these bounds
// (3 s at 60 s before; with the replay's divergence, fixed at the same time, nefertiti once ended
// at 65.8 s on a 60 s limit).
constexpr double kMinCheckpointSeconds = 0.25;
constexpr double kCheckpointSeconds = 0.5;
// The last attempt after the time limit is spent: at most this long beyond it.
constexpr double kOutOfTimeSeconds = 0.25;
// A retry halves the face count; it does not go below this.
constexpr std::size_t kMinCoarseFaces = 8;
// A coarse start with more overlapping pairs per face than this is collapsed further at once
// (when it may be), without a Tabu run: on CAD parts of slivers such starts (ADIS16480 at 1,318
// faces: 15,654 pairs, the Twin plate at 650: 8,169) still had thousands of pairs when their
// budget ended the run; the organic meshes of bench/2000 start below 4.2 per face, and
// thingi10k__73416 (7.5), whose start is sometimes unfolded, keeps its run.
constexpr std::size_t kHopelessPairsPerFace = 10;
// Iterations a split's Tabu run may take at least (base + per face of the current mesh);
// beyond, at most as many as all the work done before it (a split that needs more is stuck:
// the result becomes approximate).
constexpr std::size_t kSplitIterationsBase = 2000;
constexpr std::size_t kSplitIterationsPerFace = 5;
// Small meshes get the split work budget of this many faces (their moves are cheap, but they may
// need more of them per face). Larger ones get it times their size over this: a move tests the
// faces of the side it moves, up to half the mesh, so the tests of each split grow with the
// mesh as well as the number of splits (c3d__rocker-arm, 20,088 faces, spent a budget linear in
// its faces at 11,722 faces while every split was still being resolved in under a second).
constexpr std::size_t kSplitTestsMinFaces = 2000;
// Share of the Tabu Unfolder's walks after a split that end at a face the start face overlaps
// (TabuOptions::partner_walks): the overlaps a split leaves are few and local, and only cuts on
// the tree path between a pair can separate it. bench/1000-2000 (QQ and AUTO, seed 1): QQ
// complete 92.6 / 88.9 / 88.9 % -> 100 / 92.6 / 88.9 %, AUTO's slowest run at 2,000 faces
// 24.7 -> 13.9 s; c3d__rocker-arm's Tabu runs 24.7 -> 17.4 s (docs/performance.md).
constexpr double kSplitPartnerWalks = 1.0;

// The Tabu run of a stuck step's growth g gets (kSplitIterationsBase + kSplitIterationsPerFace *
// faces) << (g / 2) iterations, at most << kMaxGrowthShift. c3d__beetle-alt with the default
// seed, 60 s: << g reached 22,429 faces, its failed tries at 986 and 1,210 faces taking 6 s;
// << (g / 2) 24,228; the base cap alone did not separate its step of 512 splits (757 faces).
constexpr std::size_t kMaxGrowthShift = 16;

// The smaller of an iteration or test limit (0: none) and n.
std::size_t at_most(std::size_t limit, std::size_t n) {
  return limit == 0 ? n : std::min(limit, n);
}

// The Luby sequence 1 1 2 1 1 2 4 1 1 2 1 1 2 4 8 ... (i from 1): the caps of restarted runs.
// Restarting after work of this sequence's units is within a logarithmic factor of the best
// fixed cutoff for any distribution of a run's length (Luby, Sinclair and Zuckerman, "Optimal
// speedup of Las Vegas algorithms", 1993).
std::size_t luby(std::size_t i) {
  for (;;) {
    std::size_t k = 1;
    while ((std::size_t{1} << k) - 1 < i) ++k;
    if ((std::size_t{1} << k) - 1 == i) return std::size_t{1} << (k - 1);
    i -= (std::size_t{1} << (k - 1)) - 1;
  }
}

}  // namespace

ProgressiveResult unfold_progressive(const Mesh& mesh, const ProgressiveOptions& options,
                                     Progress& progress) {
  const Clock::time_point start = Clock::now();
  const double limit = options.tabu.time_limit_seconds;
  const auto remaining = [&] { return limit > 0 ? limit - seconds_since(start) : 0.0; };
  // What is left of the limit when a net of `faces` faces keeps the time the steps after the
  // uncollapse need (ProgressiveOptions::after_seconds_per_face).
  const auto left_for = [&](std::size_t faces) {
    const double after = options.after_seconds_per_face * static_cast<double>(faces);
    return remaining() - std::max(0.0, after - options.after_seconds_reserved);
  };
  ProgressiveResult result;
  const auto complete_with = [&](Net net, Relay& relay) {
    result.complete = result.overlap_free = true;
    result.mesh = mesh;
    result.net = std::move(net);
    result.face_ids.resize(mesh.faces.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) result.face_ids[f] = static_cast<int>(f);
    result.splits = result.splits_total;
    ProgressInfo done;
    relay.report(done);
    result.seconds = seconds_since(start);
    return result;
  };
  ProgressiveMesh pm = decimate(mesh, {options.strategy, options.target_faces}, progress);
  const std::size_t input_faces = pm.input_face_count();

  Relay relay(progress, start);
  relay.context.input_faces = input_faces;
  relay.context.phase = "unfold";
  std::optional<State> coarse;
  TabuStats stats;
  bool coarse_ok = false, can_go_coarser = true;
  for (std::size_t attempt = 0;; ++attempt) {
    // When the coarse mesh cannot be unfolded within a modest budget, collapse it further and
    // try again: a coarser net that uncollapses part of the way is still an approximate result.
    // The coarsest attempt gets the whole remaining budget.
    // Out of time before any coarse net: one last attempt on the coarsest mesh the collapses
    // reach, bounded by iterations (a few milliseconds at that size) and by kOutOfTimeSeconds
    // beyond the limit (for meshes whose collapses end early, such as CAD parts of high genus),
    // so that a time limit too short for the coarse mesh still gives an approximate net. Time,
    // not work, bounds it: the user's limit decides the result here anyway, and a test costs up
    // to 11 us there (the Twin plate by SEMP: 2,126 faces, 100,000 overlapping pairs).
    const bool out_of_time = limit > 0 && remaining() <= 0;
    if (out_of_time && can_go_coarser && pm.face_count() > kMinCoarseFaces) {
      const std::size_t before = pm.face_count();
      collapse_further(pm, options.strategy, kMinCoarseFaces, progress);
      if (pm.face_count() < before) ++result.coarse_retries;
      can_go_coarser = false;
    }
    const std::size_t faces = pm.face_count();
    if (attempt == 1 && !out_of_time) {
      // The coarse mesh resisted: before collapsing further, see whether the input needs no
      // search at all, the unfolding of its steepest-edge or minimum-perimeter tree being
      // overlap-free already. On CAD plates of slivers (the Twin plate) the input's
      // minimum-perimeter tree is a net while every collapsed version overlaps and the splits
      // back stall. It costs two layouts of the input, so only meshes that resist pay it.
      relay.context.faces = input_faces;
      if (std::optional<Net> net = start_tree_net(mesh, options.tabu.seed)) {
        result.coarse_faces = faces;
        result.splits_total = pm.splits_left();
        return complete_with(std::move(*net), relay);
      }
    }
    const std::size_t next = faces / 2;
    const bool last = !can_go_coarser || next < kMinCoarseFaces || out_of_time;
    relay.context.faces = faces;
    coarse = make_state(pm, mesh, options.tabu.seed + attempt, attempt > 0);
    Unfolding& u = coarse->unfolding;
    TabuOptions tabu = options.tabu;
    tabu.seed = options.tabu.seed + attempt;
    tabu.phase = "unfold";
    tabu.input_faces = input_faces;
    if (limit > 0) tabu.time_limit_seconds = std::max(1e-3, remaining());
    // The last coarse attempt leaves half the budget to plain Tabu Unfolding of the input.
    if (last && limit > 0 && faces < input_faces)
      tabu.time_limit_seconds = std::max(1e-3, remaining() / 2);
    if (out_of_time) {
      tabu.time_limit_seconds = kOutOfTimeSeconds;
      tabu.max_iterations =
          at_most(tabu.max_iterations, kCoarseIterationsBase + kCoarseIterationsPerFace * faces);
    }
    if (!last) {
      if (options.coarse_iterations > 0) {
        tabu.max_iterations = options.coarse_iterations;
      } else {
        tabu.max_iterations =
            at_most(tabu.max_iterations, kCoarseIterationsBase + kCoarseIterationsPerFace * faces);
        tabu.stall_iterations = std::max<std::size_t>(kCoarseStallBase, 5 * faces);
        // A little work per face: a coarse mesh that needs more is usually better retried
        // coarser (CAD parts of genus 20+). And a share of the time limit, which only binds
        // when that limit is short.
        tabu.max_tests =
            at_most(tabu.max_tests, std::max(kCoarseTestsMin, kCoarseTestsPerFace * faces));
        if (limit > 0) tabu.time_limit_seconds = std::max(1e-3, remaining() / 4);
      }
    }
    const bool hopeless = !last && u.overlap_count() > kHopelessPairsPerFace * faces;
    coarse_ok = !hopeless && u.resolve_overlaps(tabu, relay, &stats);
    result.stats.add(stats);
    stats = {};
    if (coarse_ok || last) break;
    collapse_further(pm, options.strategy, next, progress);
    // No legal collapse left: one more attempt on this mesh, with the whole budget.
    if (pm.face_count() >= faces) can_go_coarser = false;
    ++result.coarse_retries;
  }
  result.coarse_faces = pm.face_count();
  result.splits_total = pm.splits_left();
  if (!coarse_ok && pm.face_count() < input_faces && (limit <= 0 || left_for(input_faces) > 0)) {
    // No coarse mesh could be unfolded: plain Tabu Unfolding of the input itself with what is
    // left of the budget (unfold_tabu starts from the better of two trees; on meshes of slivers
    // such as the Twin plate the input's minimum-perimeter tree can be a net when no collapsed
    // version is unfolded).
    TabuOptions tabu = options.tabu;
    tabu.input_faces = input_faces;
    if (limit > 0) tabu.time_limit_seconds = std::max(1e-3, left_for(input_faces));
    relay.context.faces = input_faces;
    UnfoldResult full;
    try {
      full = unfold_tabu(mesh, tabu, relay);
    } catch (const InvalidInputException&) {
      // The input has no net at all (a dual graph that is a tree): keep the coarse attempt.
    }
    result.stats.add(full.stats);
    if (full.overlap_free) return complete_with(std::move(full.net), relay);
  }
  State st = std::move(*coarse);
  coarse.reset();

  bool failed = !coarse_ok;
  std::vector<Applied> log;  // splits applied since the checkpoint
  std::size_t logged_splits = 0;
  Clock::time_point last_checkpoint = Clock::now();
  // By time as well: after the time limit ends a split's Tabu run, replaying costs about the time
  // since the checkpoint, spent beyond the limit. At most kCheckpointSeconds apart, the unfold
  // ends within its limit plus about a second (a checkpoint copies the state: 10 ms at 20,000
  // faces).
  const auto checkpoint_period = std::chrono::duration<double>(
      limit > 0 ? std::clamp(limit / 20, kMinCheckpointSeconds, kCheckpointSeconds) : 1.0);
  std::optional<State> checkpoint;
  if (coarse_ok) {
    progress.intermediate(st.unfolding.mesh(), st.unfolding.net());
    checkpoint = st;
  }
  // Checkpoints cost a copy of the state: a few per run, so that going back to the last
  // overlap-free state replays at most an eighth of the splits.
  const std::size_t checkpoint_every = std::max<std::size_t>(64, result.splits_total / 8);
  relay.context.phase = "uncollapse";
  // The Tabu Unfolder's options after a split, the same when the split is replayed (then without
  // its limits but its iteration count): a replay that searched otherwise would diverge, stop
  // short of the checkpoint's splits and lose them (the partner walks once differed).
  const auto split_tabu = [&](std::uint64_t seed) {
    TabuOptions t = options.tabu;
    t.seed = seed;
    t.phase = "uncollapse";
    t.input_faces = input_faces;
    t.partner_walks = kSplitPartnerWalks;
    return t;
  };
  // Back to the checkpoint, and the first `upto` steps of the log after it replayed with their
  // seeds and iteration counts (deterministic, no time limit). Returns the steps replayed: fewer
  // when a replay diverged (its run ended with pairs left), the state then after the last.
  const auto replay = [&](std::size_t upto) {
    ++result.replays;
    relay.quiet = true;
    st = *checkpoint;
    std::size_t i = 0;
    for (; i < upto; ++i) {
      if (place_splits(st, log[i].splits, log[i].seed) == 0) continue;
      if (log[i].walk_seed != 0) {
        const LocalRepairOptions walk =
            walk_options(st.unfolding, log[i].walk_seed, log[i].walk_tests);
        if (st.unfolding.repair_locally(walk) > 0) break;
        continue;
      }
      TabuOptions t = split_tabu(log[i].tabu_seed);
      t.max_iterations = log[i].iterations;
      t.time_limit_seconds = 0;
      if (!st.unfolding.resolve_overlaps(t, relay)) break;
    }
    relay.quiet = false;
    return i;
  };
  std::size_t split_tests = 0;  // Tabu work after splits, against its budget
  // The Tabu runs after a step whose splits left pairs: Separated, Stuck (a run ended by its
  // iteration cap) or Out (of the split budget or of time).
  enum class Ended { Separated, Stuck, Out };
  const auto resolve_step = [&](Applied& step, std::size_t growth) {
    TabuOptions t = split_tabu(step.seed);
    t.time_limit_seconds = options.split_time_limit_seconds;
    const std::size_t least = kSplitIterationsBase + kSplitIterationsPerFace * pm.face_count();
    t.max_iterations =
        options.split_iterations > 0 ? options.split_iterations
        : growth > 0
            ? at_most(t.max_iterations, least << std::min<std::size_t>(growth / 2, kMaxGrowthShift))
            : at_most(t.max_iterations, std::max(least, result.stats.iterations));
    if (limit > 0) t.time_limit_seconds = std::min(t.time_limit_seconds, left_for(pm.face_count()));
    if (options.split_tests_per_face > 0) {
      const std::size_t budget = options.split_tests_per_face *
                                 std::max(input_faces, kSplitTestsMinFaces) *
                                 std::max<std::size_t>(1, input_faces / kSplitTestsMinFaces);
      if (split_tests >= budget) return Ended::Out;
      t.max_tests = budget - split_tests;
    }
    if (limit > 0 && t.time_limit_seconds <= 0) return Ended::Out;
    // A run still searching after its share of tests starts again from the same state with
    // another seed (ProgressiveOptions::restart_faces): only the last run counts for the replay.
    const bool restart = options.restart_faces > 0 && pm.face_count() >= options.restart_faces;
    const std::size_t unit = options.restart_tests_per_face * pm.face_count();
    for (std::size_t r = 0;; ++r) {
      const std::size_t cap = unit * luby(r + 1);
      TabuOptions run = t;
      run.seed = step.tabu_seed;
      if (limit > 0)
        run.time_limit_seconds =
            std::max(1e-3, std::min(run.time_limit_seconds, left_for(pm.face_count())));
      const bool capped = restart && cap > 0 && (t.max_tests == 0 || cap < t.max_tests);
      std::optional<State> before;
      if (capped) {
        run.max_tests = cap;
        before = st;
      }
      TabuStats ran;
      const bool ok = st.unfolding.resolve_overlaps(run, relay, &ran);
      result.stats.add(ran);
      split_tests += ran.tests;
      step.iterations = ran.iterations;
      if (ok) return Ended::Separated;
      const bool out = (t.max_tests > 0 && ran.tests >= t.max_tests) ||
                       (limit > 0 && left_for(pm.face_count()) <= 0);
      // Ended by another limit than its cap: its iterations (stuck), the split budget or time.
      if (out || !capped || ran.tests < cap)
        return !out && run.max_iterations > 0 && ran.iterations >= run.max_iterations ? Ended::Stuck
                                                                                      : Ended::Out;
      if (t.max_tests > 0) t.max_tests -= ran.tests;
      if (options.walk_after_restarts > 0 && r + 1 >= options.walk_after_restarts) {
        // A walk of local moves from the same state, within the same cap, and within the local
        // repair's budget after a split: like that repair, a walk checks neither the time limit
        // nor cancellation, and the Luby caps grow without bound.
        st = *before;
        const std::uint64_t seed = split_seed(step.tabu_seed, ~r) | 1;
        std::size_t tests = std::min(cap, repair_tests(st.unfolding));
        if (t.max_tests > 0) tests = std::min(tests, t.max_tests);
        LocalRepairStats walked;
        const bool separated =
            st.unfolding.repair_locally(walk_options(st.unfolding, seed, tests), &walked) == 0;
        split_tests += walked.tests;
        if (separated) {
          step.walk_seed = seed;
          step.walk_tests = tests;
          ++result.walks;
          return Ended::Separated;
        }
        if (t.max_tests > 0) {
          if (walked.tests >= t.max_tests) {
            st = std::move(*before);
            return Ended::Out;
          }
          t.max_tests -= walked.tests;
        }
      }
      st = std::move(*before);
      ++result.restarts;
      step.tabu_seed = split_seed(step.tabu_seed, r);
    }
  };
  Clock::time_point last_output = Clock::now();
  std::size_t index = 0;
  while (!failed && pm.splits_left() > 0) {
    if (progress.cancelled()) throw CancelledException();
    // The time limit ends the uncollapse also between splits that need no search: the state is
    // overlap-free here, an approximate result.
    if (limit > 0 && left_for(pm.face_count()) <= 0) break;
    // A few splits per update: the parts they move are re-laid out and tested once; on large
    // meshes batches also keep the O(faces) cost of a full update per face added bounded.
    Applied step;
    step.seed = step.tabu_seed = split_seed(options.tabu.seed, index++);
    const std::size_t batch = options.splits_per_update > 0
                                  ? options.splits_per_update
                                  : std::max(kSplitsPerUpdate, pm.face_count() / kBatchFaces);
    for (std::size_t i = 0; i < batch && pm.splits_left() > 0; ++i)
      step.splits.push_back(pm.split());
    for (std::size_t growth = 0;; ++growth) {
      relay.context.faces = pm.face_count();
      const Ended ended = place_splits(st, step.splits, step.seed) == 0
                              ? Ended::Separated
                              : resolve_step(step, growth);
      if (ended == Ended::Separated) break;
      if (ended == Ended::Out || growth >= options.stuck_step_growths || pm.splits_left() == 0 ||
          !checkpoint || (limit > 0 && left_for(pm.face_count()) <= 0)) {
        failed = true;
        break;
      }
      // Stuck (ProgressiveOptions::stuck_step_growths): back to the state before the step, which
      // is applied again with as many splits more. The stuck state stays if the replay diverged.
      State stuck_here = std::move(st);
      if (replay(log.size()) < log.size()) {
        st = std::move(stuck_here);
        failed = true;
        break;
      }
      ++result.growths;
      step.tabu_seed = step.seed;
      for (std::size_t i = step.splits.size(); i > 0 && pm.splits_left() > 0; --i)
        step.splits.push_back(pm.split());
    }
    if (failed) break;
    logged_splits += step.splits.size();
    log.push_back(std::move(step));
    if (logged_splits >= checkpoint_every || Clock::now() - last_checkpoint > checkpoint_period) {
      checkpoint = st;
      log.clear();
      logged_splits = 0;
      last_checkpoint = Clock::now();
    }
    if (Clock::now() - last_output > std::chrono::milliseconds(100)) {
      last_output = Clock::now();
      relay.report(ProgressInfo{});
      progress.intermediate(st.unfolding.mesh(), st.unfolding.net());
    }
  }

  std::optional<State> stuck;  // where the uncollapse stopped, for complete_first
  if (failed && checkpoint) {
    if (options.complete_first) stuck = st;
    // Back to the last overlap-free state: the checkpoint plus the splits that followed it,
    // replayed with their seeds and iteration counts (deterministic, no time limit).
    for (std::size_t upto = log.size();;) {
      const std::size_t done = replay(upto);
      if (done == upto) break;
      upto = done;
    }
  }

  if (stuck && (limit <= 0 || left_for(input_faces) > 0)) {
    TabuOptions t = options.tabu;
    t.phase = "uncollapse";
    t.input_faces = input_faces;
    if (limit > 0) t.time_limit_seconds = std::max(1e-3, left_for(input_faces));
    if (options.complete_first_seconds > 0)
      t.time_limit_seconds = t.time_limit_seconds > 0
                                 ? std::min(t.time_limit_seconds, options.complete_first_seconds)
                                 : options.complete_first_seconds;
    relay.context.faces = input_faces;
    UnfoldResult full;
    try {
      full = finish_on_input(std::move(*stuck), pm, mesh, options.tabu.seed, index, t, relay);
    } catch (const InvalidInputException&) {
      // The input has no net at all (a dual graph that is a tree): keep the approximation.
    }
    stuck.reset();
    result.stats.add(full.stats);
    if (full.overlap_free) {
      result.continued = true;
      return complete_with(std::move(full.net), relay);
    }
  }
  result.splits = st.splits;
  result.overlaps = st.unfolding.overlap_count();
  result.overlap_free = result.overlaps == 0;
  result.complete = result.overlap_free && st.unfolding.face_count() == input_faces;
  if (result.complete) {
    result.mesh = mesh;
    result.net = net_in_input_ids(st, input_faces);
    result.face_ids.resize(input_faces);
    for (std::size_t f = 0; f < input_faces; ++f) result.face_ids[f] = static_cast<int>(f);
  } else {
    result.mesh = st.unfolding.mesh();
    result.net = st.unfolding.net();
    result.face_ids.assign(st.unfolding.face_count(), -1);
    for (std::size_t f = 0; f < input_faces; ++f)
      if (st.face[f] >= 0) result.face_ids[st.face[f]] = static_cast<int>(f);
    if (result.overlap_free) {
      result.hausdorff = approximation_distance(mesh, result.mesh);
    }
  }
  relay.context.faces = result.mesh.faces.size();
  ProgressInfo last;
  last.overlaps = result.overlaps;
  relay.report(last);
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace papernet
