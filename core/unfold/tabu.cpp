// The Tabu Unfolder (docs/architecture.md, "The unfolder") over the incremental state of an
// Unfolding: Unfolding::resolve_overlaps and unfold_tabu.
#include "core/unfold/tabu.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/mesh/dual_graph.h"
#include "core/random.h"
#include "core/unfold/unfolding.h"

namespace papernet {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A dual edge {a, b} as an ordered pair.
std::pair<int, int> dual_edge(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

}  // namespace

bool Unfolding::resolve_overlaps(const TabuOptions& options, Progress& progress, TabuStats* stats) {
  const Clock::time_point start = Clock::now();
  update();  // pending edits
  const int nf = static_cast<int>(face_count());
  const std::size_t walks = std::max<std::size_t>(1, options.walks);
  const long long accept_rise =
      static_cast<long long>(std::min<std::size_t>(options.accept_rise, 1u << 30));
  Random rng(options.seed);

  // Tabu list length m = val * log_val(|F|), val the average valence of the dual graph.
  std::size_t twice_edges = 0;
  for (const auto& n : adj_)
    for (int q : n) twice_edges += q >= 0 ? 1 : 0;
  const double val = static_cast<double>(twice_edges) / nf;
  const std::size_t tabu_length =
      val > 1.01 && nf > 1 ? static_cast<std::size_t>(std::ceil(val * std::log(nf) / std::log(val)))
                           : 1;
  // A dual graph that is itself a tree (open, heavily decimated meshes: every interior edge is a
  // bridge) has a single spanning tree: no move exists, so overlaps cannot be resolved.
  const bool no_moves = twice_edges / 2 + 1 == static_cast<std::size_t>(nf);
  std::deque<std::pair<int, int>> tabu;
  const auto is_tabu = [&tabu](int a, int b) {
    return std::find(tabu.begin(), tabu.end(), dual_edge(a, b)) != tabu.end();
  };

  TabuStats st;
  const std::size_t tested_before = tested_;
  ProgressInfo info;
  info.phase = options.phase;
  info.faces = face_count();
  info.input_faces = options.input_faces ? options.input_faces : face_count();
  const auto report = [&] {
    info.overlaps = pair_count_;
    info.iterations = st.iterations;
    info.elapsed_seconds = seconds_since(start);
    progress.report(info);
  };
  report();
  Clock::time_point last_report = Clock::now();

  for (int f = 0; f < nf; ++f)
    if (parent_[f] == -1) root_at(f);
  // Checked between iterations and every few evaluations inside one: on huge sliver meshes a
  // single walk can take seconds.
  const auto out_of_time = [&](Clock::time_point now) {
    return options.time_limit_seconds > 0 &&
           std::chrono::duration<double>(now - start).count() >= options.time_limit_seconds;
  };
  bool stop = false;
  bool stalled = false;  // no new fewest count for |F| iterations: more walks from now on
  bool moved = false;
  std::size_t fewest = pair_count_, fewest_at = 0;
  for (;;) {
    if (pair_count_ == 0) {
      // Moves are rigid motions, which round; lay the net out exactly from its tree again.
      if (!moved) break;
      relayout_all();
      moved = false;
      continue;
    }
    if (pair_count_ < fewest) fewest = pair_count_, fewest_at = st.iterations;
    if (options.stall_iterations && st.iterations - fewest_at >= options.stall_iterations) break;
    if (no_moves || (options.max_iterations && st.iterations >= options.max_iterations)) break;
    const Clock::time_point now = Clock::now();
    if (out_of_time(now)) break;
    if (progress.cancelled()) throw CancelledException();
    if (now - last_report >= std::chrono::milliseconds(50)) {
      report();
      last_report = now;
    }

    int best_g = -1, best_k = -1, best_other = -1;
    long long best_delta = LLONG_MAX;
    bool blocked = false, improved = false;
    // Walks from a random overlapping face towards a random root (re-rooting moves nothing, so
    // the root is only where the walk ends; the pre-order stays as it is), or, for a share
    // `partner_walks` of the walks, towards a face it overlaps. Once stalled, when
    // the best move of the walks so far raises the count by more than accept_rise pairs,
    // another walk looks elsewhere; then the best move of all of them is applied.
    if (st.iterations - fewest_at > static_cast<std::size_t>(nf)) stalled = true;
    const std::size_t now_walks = stalled ? walks : 1;
    for (std::size_t walk = 0; walk < now_walks && best_delta > accept_rise && !stop; ++walk) {
      int r = static_cast<int>(rng.below(nf));
      sort_overlapping();
      const int f = overlapping_[rng.below(overlapping_.size())];
      if (options.partner_walks > 0 && rng.uniform() < options.partner_walks) {
        const std::vector<int>& partners = overlaps_[f];
        r = partners[rng.below(partners.size())];
      }
      for (int g = f; g != r && !improved && !stop;) {
        const int up = step_towards(g, r);
        cut(g, up);
        long long crossing = -1;  // computed once per cut, when a move is evaluated
        for (int k = 0; k < 3 && !improved; ++k) {
          const int q = adj_[g][k];
          if (q < 0 || (links_[g] >> k & 1) || in_subtree(q)) continue;
          if (is_tabu(g, q)) {
            blocked = true;
            continue;
          }
          if (crossing < 0) crossing = crossing_pairs();
          const long long delta = evaluate_move(g, k, crossing, best_delta);
          ++st.evaluations;
          if (out_of_time(Clock::now()) ||
              (options.max_tests && tested_ - tested_before >= options.max_tests))
            stop = true;
          if (st.evaluations % 32 == 0 && progress.cancelled()) throw CancelledException();
          if (delta < best_delta) best_delta = delta, best_g = g, best_k = k, best_other = up;
          if (delta < 0) improved = true;
        }
        g = up;
      }
    }
    ++st.iterations;
    if (stop) break;
    if (best_g < 0) {
      if (blocked) tabu.clear();
      continue;
    }
    cut(best_g, best_other);
    apply_move(best_g, best_k);
    moved = true;
    tabu.push_back(dual_edge(best_g, best_other));
    if (tabu.size() > tabu_length) tabu.pop_front();
  }
  if (moved) relayout_all();
  st.tests = tested_ - tested_before;
  st.seconds = seconds_since(start);
  report();
  if (stats) *stats = st;
  return pair_count_ == 0;
}

namespace {

// Work of unfold_tabu_from's attempt from its start tree, per face (TabuStats::tests): the
// successful ones on the CAD parts of bench/800-2000 needed up to 11,510 (docs/performance.md).
constexpr std::size_t kStartTestsPerFace = 15'000;

// unfold_tabu's attempts; attempt 0 starts from `start` (a parent per face) when given.
UnfoldResult tabu_attempts(const Mesh& mesh, const std::vector<int>* start,
                           const TabuOptions& options, Progress& progress) {
  const Clock::time_point begin = Clock::now();
  UnfoldResult result;
  std::optional<Unfolding> best;
  std::size_t iterations_left = options.max_iterations;
  for (std::uint64_t attempt = 0;; ++attempt) {
    // With a start tree, it is attempt 0 and the plain runs follow; those are numbered k.
    const bool from_start = start && attempt == 0;
    const std::uint64_t k = start ? attempt - 1 : attempt;
    // Plain attempt 0 runs from options.seed; later ones start from other directions.
    const std::uint64_t seed =
        from_start || k == 0 ? options.seed : options.seed ^ (k * 0x9e3779b97f4a7c15ull);
    Unfolding unfolding =
        from_start ? Unfolding(mesh, *start) : Unfolding::steepest_edge(mesh, seed);
    if (!from_start && k == 0) {
      // The minimum-perimeter tree keeps slivers glued along their long sides: on CAD meshes
      // it starts with far fewer overlaps than steepest edges (5,756-face Twin plate: 273
      // pairs against 22,000-320,000); on organic meshes usually with more.
      Unfolding other(mesh, min_perimeter_tree(mesh, build_dual_graph(mesh), seed));
      if (other.overlap_count() < unfolding.overlap_count()) unfolding = std::move(other);
    }
    if (attempt == 0 && unfolding.overlap_count() > 0 && build_dual_graph(mesh).is_tree())
      throw InvalidInputException(
          "its dual graph is a tree (every edge between two faces must stay uncut to keep the "
          "net in one piece), so it has a single edge unfolding, and that one has " +
          std::to_string(unfolding.overlap_count()) + " overlapping face pairs");
    TabuOptions rest = options;
    rest.seed = seed;
    rest.max_iterations = iterations_left;
    if (options.max_tests) rest.max_tests = options.max_tests - result.stats.tests;
    // Allowed stall: generous on the first attempt, growing each restart.
    const std::size_t nf = unfolding.face_count();
    // A start tree gets a shorter one, and at most kStartTestsPerFace moved-face tests: when it
    // leads nowhere, the plain attempts follow.
    rest.stall_iterations = from_start ? std::max<std::size_t>(10'000, 5 * nf)
                                       : std::max<std::size_t>(20'000, 20 * nf)
                                             << std::min<std::uint64_t>(k, 20);
    if (from_start && (rest.max_tests == 0 || rest.max_tests > kStartTestsPerFace * nf))
      rest.max_tests = kStartTestsPerFace * nf;
    if (options.time_limit_seconds > 0)
      rest.time_limit_seconds = std::max(1e-3, options.time_limit_seconds - seconds_since(begin));
    TabuStats st;
    const bool ok = unfolding.resolve_overlaps(rest, progress, &st);
    result.stats.add(st);
    if (!best || unfolding.overlap_count() < best->overlap_count()) best = std::move(unfolding);
    if (ok || st.iterations == 0) break;  // 0: no move exists, or the budget is spent
    if (options.max_iterations) {
      iterations_left -= std::min(iterations_left, st.iterations);
      if (iterations_left == 0) break;
    }
    if (options.max_tests && result.stats.tests >= options.max_tests) break;
    if (options.time_limit_seconds > 0 && seconds_since(begin) >= options.time_limit_seconds) break;
  }
  result.overlap_free = best->overlap_count() == 0;
  result.overlaps = best->overlap_count();
  result.stats.seconds = seconds_since(begin);
  result.net = best->net();
  return result;
}

}  // namespace

UnfoldResult unfold_tabu(const Mesh& mesh, const TabuOptions& options, Progress& progress) {
  return tabu_attempts(mesh, nullptr, options, progress);
}

UnfoldResult unfold_tabu_from(const Mesh& mesh, const std::vector<int>& parent,
                              const TabuOptions& options, Progress& progress) {
  return tabu_attempts(mesh, &parent, options, progress);
}

}  // namespace papernet
