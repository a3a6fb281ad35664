// The Tabu Unfolder (DESIGN.md §3) over the incremental state of an Unfolding.
#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <deque>
#include <utility>

#include "core/errors.h"
#include "core/random.h"
#include "core/unfolding.h"

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
  Random rng(options.seed);

  // Tabu list length m = val * log_val(|F|), val the average valence of the dual graph.
  std::size_t twice_edges = 0;
  for (const auto& n : adj_)
    for (int q : n) twice_edges += q >= 0 ? 1 : 0;
  const double val = static_cast<double>(twice_edges) / nf;
  const std::size_t tabu_length =
      val > 1.01 && nf > 1 ? static_cast<std::size_t>(std::ceil(val * std::log(nf) / std::log(val)))
                           : 1;
  std::deque<std::pair<int, int>> tabu;
  const auto is_tabu = [&tabu](int a, int b) {
    return std::find(tabu.begin(), tabu.end(), dual_edge(a, b)) != tabu.end();
  };

  TabuStats st;
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

  bool moved = false;
  for (;;) {
    if (pair_count_ == 0) {
      // Moves are rigid motions, which round; lay the net out exactly from its tree again.
      if (!moved) break;
      relayout_all();
      moved = false;
      continue;
    }
    if (options.max_iterations && st.iterations >= options.max_iterations) break;
    const Clock::time_point now = Clock::now();
    if (options.time_limit_seconds > 0 &&
        std::chrono::duration<double>(now - start).count() >= options.time_limit_seconds)
      break;
    if (progress.cancelled()) throw CancelledException();
    if (now - last_report >= std::chrono::milliseconds(50)) {
      report();
      last_report = now;
    }

    root_at(static_cast<int>(rng.below(nf)));
    const int f = overlapping_[rng.below(overlapping_.size())];
    int best_g = -1, best_k = -1;
    long long best_delta = LLONG_MAX;
    bool blocked = false, improved = false;
    for (int g = f; parent_[g] != -1 && !improved; g = parent_[g]) {
      cut(g);
      for (int k = 0; k < 3 && !improved; ++k) {
        const int q = adj_[g][k];
        if (q < 0 || (links_[g] >> k & 1) || in_subtree(q)) continue;
        if (is_tabu(g, q)) {
          blocked = true;
          continue;
        }
        const long long delta = evaluate_move(g, k, best_delta);
        ++st.evaluations;
        if (delta < best_delta) best_delta = delta, best_g = g, best_k = k;
        if (delta < 0) improved = true;
      }
    }
    ++st.iterations;
    if (best_g < 0) {
      if (blocked) tabu.clear();
      continue;
    }
    const int old_parent = parent_[best_g];
    cut(best_g);
    apply_move(best_g, best_k);
    moved = true;
    tabu.push_back(dual_edge(best_g, old_parent));
    if (tabu.size() > tabu_length) tabu.pop_front();
  }
  if (moved) relayout_all();
  st.seconds = seconds_since(start);
  report();
  if (stats) *stats = st;
  return pair_count_ == 0;
}

UnfoldResult unfold_tabu(const Mesh& mesh, const TabuOptions& options, Progress& progress) {
  const Clock::time_point start = Clock::now();
  Unfolding unfolding = Unfolding::steepest_edge(mesh, options.seed);
  UnfoldResult result;
  TabuOptions rest = options;
  if (options.time_limit_seconds > 0)
    rest.time_limit_seconds = std::max(1e-3, options.time_limit_seconds - seconds_since(start));
  result.overlap_free = unfolding.resolve_overlaps(rest, progress, &result.stats);
  result.overlaps = unfolding.overlap_count();
  result.stats.seconds = seconds_since(start);
  result.net = unfolding.net();
  return result;
}

}  // namespace papernet
