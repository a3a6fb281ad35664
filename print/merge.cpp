// Pieces merged by unfolding two at a time anew (print/fit.h, merge_pieces).
#include <algorithm>
#include <chrono>
#include <functional>
#include <set>
#include <utility>

#include "core/errors.h"
#include "core/mesh/dual_graph.h"
#include "core/tabs/tab_clearance.h"
#include "core/unfold/net_metrics.h"
#include "core/unfold/tabu.h"
#include "print/fit.h"
#include "print/internal/number_pieces.h"

namespace papernet {
namespace {

// Unfold trees of the faces `together` (sorted; the faces of pieces p and q, each a tree of
// `parent`), as indices into `together`: p's tree and q's, hung from p across one of the edges
// they share, q's tree turned to hang from that edge's face. Up to `count`, across edges spread
// over those they share.
std::vector<std::vector<int>> glued_trees(const DualGraph& graph, const std::vector<int>& parent,
                                          const std::vector<int>& piece,
                                          const std::vector<int>& together, int p, int q,
                                          int count) {
  const auto local = [&](int f) {
    return static_cast<int>(std::lower_bound(together.begin(), together.end(), f) -
                            together.begin());
  };
  std::vector<int> tree(together.size());
  for (std::size_t i = 0; i < together.size(); ++i) {
    const int up = parent[together[i]];
    tree[i] = up < 0 ? -1 : local(up);
  }
  std::vector<std::pair<int, int>> shared;  // (face of p, face of q)
  for (int f : together)
    if (piece[f] == p)
      for (int k = 0; k < 3; ++k) {
        const int g = graph.neighbour[f][k];
        if (g >= 0 && piece[g] == q) shared.push_back({f, g});
      }
  std::vector<std::vector<int>> out;
  if (shared.empty() || count <= 0) return out;
  const std::size_t n = std::min(shared.size(), static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < n; ++i) {
    const auto [f, g] = shared[i * shared.size() / n];
    std::vector<int> glued = tree;
    // q's tree turned at g: each face on the path from g to q's root hangs from the one before.
    int at = local(g), from = local(f);
    while (at >= 0) {
      const int up = glued[at];
      glued[at] = from;
      from = at;
      at = up;
    }
    out.push_back(std::move(glued));
  }
  return out;
}

}  // namespace

FitPieces merge_pieces(const Mesh& mesh, const std::vector<int>& part, FitPieces pieces,
                       double scale, FitRoom room, const TabClearanceOptions& tabs,
                       const MergeBudget& budget, const std::function<bool(const FitPieces&)>& keep,
                       Progress* progress) {
  const auto n = static_cast<int>(mesh.faces.size());
  const DualGraph graph = build_dual_graph(mesh);
  std::size_t tests_left = budget.tests;
  std::size_t evaluations_left = budget.tab_evaluations;
  std::size_t asks_left = budget.keeps;
  // Pairs that no try merged, or whose merge was not kept, as their faces (a pair's faces stay
  // the same while neither piece changes).
  std::set<std::vector<int>> failed;
  Progress quiet;
  using Clock = std::chrono::steady_clock;
  const Clock::time_point started = Clock::now();
  // The time left, or 0 without a bound; below zero when the time is up.
  const auto left = [&] {
    if (budget.seconds <= 0) return 0.0;
    const double t = budget.seconds - std::chrono::duration<double>(Clock::now() - started).count();
    return t > 0 ? t : -1.0;
  };
  // A time limit for a step: what is left (0: none).
  const auto limit = [&] { return budget.seconds <= 0 ? 0.0 : std::max(left(), 1e-3); };
  // The share of the budget used: of whichever bound is nearest.
  const auto report = [&] {
    if (!progress) return;
    if (progress->cancelled()) throw CancelledException();
    const auto used = [](std::size_t left_over, std::size_t all) {
      return all == 0 ? 0.0 : 1.0 - static_cast<double>(left_over) / static_cast<double>(all);
    };
    ProgressInfo info;
    info.phase = "merge";
    info.faces = info.input_faces = mesh.faces.size();
    info.phase_fraction =
        std::max({used(tests_left, budget.tests), used(evaluations_left, budget.tab_evaluations),
                  keep ? used(asks_left, budget.keeps) : 0.0});
    if (budget.seconds > 0)
      info.phase_fraction =
          std::max(info.phase_fraction, left() < 0 ? 1.0 : 1.0 - left() / budget.seconds);
    progress->report(info);
  };
  for (bool merged = true; merged && tests_left > 0 && asks_left > 0 && left() >= 0;) {
    merged = false;
    const std::vector<int>& of = pieces.piece;
    std::vector<std::vector<int>> members(static_cast<std::size_t>(pieces.pieces));
    std::vector<char> fixed(members.size(), 0);  // a piece of a face larger than the room
    for (int f = 0; f < n; ++f) {
      members[of[f]].push_back(f);
      if (!pieces.large.empty() && pieces.large[f]) fixed[of[f]] = 1;
    }
    // The pairs of pieces across an edge of one part, the fewest faces first.
    std::set<std::pair<int, int>> across;
    for (int f = 0; f < n; ++f)
      for (int k = 0; k < 3; ++k) {
        const int g = graph.neighbour[f][k];
        if (g < 0 || of[g] == of[f] || part[g] != part[f] || fixed[of[f]] || fixed[of[g]]) continue;
        across.insert({std::min(of[f], of[g]), std::max(of[f], of[g])});
      }
    std::vector<std::pair<int, int>> pairs(across.begin(), across.end());
    const auto faces = [&](std::pair<int, int> p) {
      return members[p.first].size() + members[p.second].size();
    };
    std::stable_sort(pairs.begin(), pairs.end(),
                     [&](auto a, auto b) { return faces(a) < faces(b); });
    for (const auto& [p, q] : pairs) {
      std::vector<int> together = members[p];
      together.insert(together.end(), members[q].begin(), members[q].end());
      std::sort(together.begin(), together.end());
      if (failed.count(together)) continue;
      const Mesh both = mesh_of_faces(mesh, together);
      const auto fits = [&](const Net& net) {
        std::vector<Vec2> corners;
        for (const auto& t : net.points)
          for (Vec2 c : t) corners.push_back(scale * c);
        return hull_fits(convex_hull(std::move(corners)), room.room);
      };
      // First from the two pieces' own trees glued across an edge they share (most merges need
      // only a few moves from there), then from the Tabu Unfolder's own starts.
      const std::vector<std::vector<int>> glued =
          glued_trees(graph, pieces.net.parent, of, together, p, q, budget.glued);
      const int attempts = static_cast<int>(glued.size()) + budget.tries;
      for (int a = 0; a < attempts && tests_left > 0 && !merged && left() >= 0; ++a) {
        const bool from_glued = a < static_cast<int>(glued.size());
        TabuOptions options;
        options.seed = static_cast<std::uint64_t>(from_glued ? a + 1 : a + 1 - glued.size());
        options.time_limit_seconds = limit();
        options.max_tests = std::min(tests_left, budget.tests_per_face * together.size());
        // Rounds whose moves are all tabu test nothing: bounded too.
        options.max_iterations = budget.iterations_per_face * together.size();
        UnfoldResult result;
        try {
          result = from_glued ? unfold_tabu_from(both, glued[a], options, quiet)
                              : unfold_tabu(both, options, quiet);
        } catch (const InvalidInputException&) {
          break;  // no single piece: faces that meet at a vertex only, or a tree that overlaps
        }
        tests_left -= std::min(tests_left, std::max<std::size_t>(result.stats.tests, 1));
        report();
        if (!result.overlap_free || !fits(result.net)) continue;
        if (tabs.min_height > 0 && !edges_without_tab_room(both, result.net, tabs).empty()) {
          if (evaluations_left == 0) continue;
          TabClearanceOptions clear = tabs;
          clear.max_evaluations =
              std::min(evaluations_left, budget.tab_evaluations_per_face * together.size());
          clear.time_limit_seconds = limit();
          TabClearanceResult cleared = clear_tab_room(both, result.net, clear, quiet);
          evaluations_left -= std::min(evaluations_left, cleared.evaluations);
          report();
          if (cleared.blocked_after > 0 || !fits(cleared.net)) continue;
          result.net = std::move(cleared.net);
        }
        // q's faces join p, every face where the new net puts it.
        FitPieces candidate = pieces;
        for (std::size_t i = 0; i < together.size(); ++i) {
          const int f = together[i];
          const int up = result.net.parent[i];
          candidate.net.parent[f] = up < 0 ? -1 : together[up];
          candidate.net.points[f] = result.net.points[i];
          candidate.piece[f] = p;
        }
        print_detail::number_pieces(candidate.piece, part, candidate);
        if (keep) {
          --asks_left;
          const bool kept = keep(candidate);
          report();
          if (!kept) break;  // the pair's first merge tells; the next pair
        }
        pieces = std::move(candidate);
        merged = true;
      }
      if (merged || asks_left == 0 || left() < 0) break;
      failed.insert(std::move(together));
    }
  }
  return pieces;
}

}  // namespace papernet
