// Pieces merged by unfolding two at a time anew (print/fit.h, merge_pieces).
#include <algorithm>
#include <chrono>
#include <functional>
#include <optional>
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

// Piece b's faces split between its neighbours a and c, at each of `shares` (fractions of b's
// faces that join a, roughly): a face joins a when it is nearer a than c across b (in faces) by
// the split's margin or more, else c; each side is then connected to its neighbour.
// Of each split, `faces[0]` holds a's faces and those of b that join it (sorted), and `trees[0]`
// an unfold tree of them as indices into `faces[0]`: a's tree, each of b's faces hanging from the
// face before it on its way to a; `faces[1]` and `trees[1]` the same for c. Splits where a side
// gets none of b's faces (a merge of a pair) and splits made before are left out.
struct Split {
  std::vector<int> faces[2];
  std::vector<int> trees[2];
};

std::vector<Split> splits_between(const DualGraph& graph, const std::vector<int>& parent,
                                  const std::vector<int>& piece,
                                  const std::vector<std::vector<int>>& members, int b, int a, int c,
                                  const std::vector<double>& shares) {
  // Breadth-first over b from the faces beside a, and from those beside c: each face's distance
  // and the face before it on the way.
  const int to[2] = {a, c};
  std::vector<int> distance[2], from[2];
  for (int s = 0; s < 2; ++s) {
    distance[s].assign(piece.size(), -1);
    from[s].assign(piece.size(), -1);
    std::vector<int> queue;
    for (int f : members[b])
      for (int k = 0; k < 3 && distance[s][f] < 0; ++k) {
        const int g = graph.neighbour[f][k];
        if (g >= 0 && piece[g] == to[s]) {
          distance[s][f] = 0;
          from[s][f] = g;
          queue.push_back(f);
        }
      }
    for (std::size_t i = 0; i < queue.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const int g = graph.neighbour[queue[i]][k];
        if (g < 0 || piece[g] != b || distance[s][g] >= 0) continue;
        distance[s][g] = distance[s][queue[i]] + 1;
        from[s][g] = queue[i];
        queue.push_back(g);
      }
    if (queue.size() != members[b].size()) return {};  // b in two (never: a piece is a tree)
  }
  // How much nearer a each face is. The face before a face on its way to a is nearer a by as
  // much or more, and the one before it on its way to c by as much or less: each side connected.
  const auto nearer = [&](int f) { return distance[1][f] - distance[0][f]; };
  std::vector<int> margins;
  for (int f : members[b]) margins.push_back(nearer(f));
  std::sort(margins.begin(), margins.end());
  std::vector<Split> out;
  std::set<int> made;
  for (double share : shares) {
    // The margin above which a face joins a: the share's quantile, from the nearest to c.
    const auto at = static_cast<std::size_t>((1 - share) * static_cast<double>(margins.size()));
    const int margin = margins[std::min(at, margins.size() - 1)];
    if (!made.insert(margin).second) continue;
    Split split;
    bool empty = false;
    for (int s = 0; s < 2; ++s) {
      std::vector<int>& faces = split.faces[s];
      faces = members[to[s]];
      const std::size_t own = faces.size();
      for (int f : members[b])
        if ((nearer(f) >= margin) == (s == 0)) faces.push_back(f);
      empty = empty || faces.size() == own;
      std::sort(faces.begin(), faces.end());
      const auto local = [&](int f) {
        return static_cast<int>(std::lower_bound(faces.begin(), faces.end(), f) - faces.begin());
      };
      std::vector<int>& tree = split.trees[s];
      tree.resize(faces.size());
      for (std::size_t i = 0; i < faces.size(); ++i) {
        const int f = faces[i];
        const int up = piece[f] == b ? from[s][f] : parent[f];
        tree[i] = up < 0 ? -1 : local(up);
      }
    }
    if (!empty) out.push_back(std::move(split));
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
  // `together`'s faces (sorted) unfolded anew as one piece that lies flat without overlap, fits
  // the room and, with tabs, leaves room for a tab on every cut inside it: from each tree of
  // `starts` (indices into `together`), then from the Tabu Unfolder's starts of seeds 1 to
  // `tries`, each of at most `tests_per_face` tests per face. None when no unfolding does within
  // the budget, or the faces make no single piece.
  const auto unfold_fitting = [&](const std::vector<int>& together,
                                  const std::vector<std::vector<int>>& starts, int tries,
                                  std::size_t tests_per_face) -> std::optional<Net> {
    const Mesh both = mesh_of_faces(mesh, together);
    const auto fits = [&](const Net& net) {
      std::vector<Vec2> corners;
      for (const auto& t : net.points)
        for (Vec2 c : t) corners.push_back(scale * c);
      return hull_fits(convex_hull(std::move(corners)), room.room);
    };
    const int attempts = static_cast<int>(starts.size()) + tries;
    for (int a = 0; a < attempts && tests_left > 0 && left() >= 0; ++a) {
      const bool from_start = a < static_cast<int>(starts.size());
      TabuOptions options;
      options.seed = static_cast<std::uint64_t>(from_start ? a + 1 : a + 1 - starts.size());
      options.time_limit_seconds = limit();
      options.max_tests = std::min(tests_left, tests_per_face * together.size());
      // Rounds whose moves are all tabu test nothing: bounded too.
      options.max_iterations = budget.iterations_per_face * together.size();
      UnfoldResult result;
      try {
        result = from_start ? unfold_tabu_from(both, starts[a], options, quiet)
                            : unfold_tabu(both, options, quiet);
      } catch (const InvalidInputException&) {
        return std::nullopt;  // no single piece: faces that meet at a vertex only, or a tree that
                              // overlaps
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
      return std::move(result.net);
    }
    return std::nullopt;
  };
  // The faces `together` made piece p of `into`, each where `net` (of them) puts it.
  const auto join = [](FitPieces& into, const std::vector<int>& together, const Net& net, int p) {
    for (std::size_t i = 0; i < together.size(); ++i) {
      const int f = together[i];
      const int up = net.parent[i];
      into.net.parent[f] = up < 0 ? -1 : together[up];
      into.net.points[f] = net.points[i];
      into.piece[f] = p;
    }
  };
  // A merge offered to `keep`; true when it may be made.
  const auto offer = [&](FitPieces& candidate) {
    print_detail::number_pieces(candidate.piece, part, candidate);
    if (!keep) return true;
    --asks_left;
    const bool kept = keep(candidate);
    report();
    return kept;
  };
  // Splits of a piece between two of its neighbours that no try made, or that were not kept.
  std::set<std::vector<int>> failed_splits;
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
      // First from the two pieces' own trees glued across an edge they share (most merges need
      // only a few moves from there), then from the Tabu Unfolder's own starts.
      if (const std::optional<Net> net = unfold_fitting(
              together, glued_trees(graph, pieces.net.parent, of, together, p, q, budget.glued),
              budget.tries, budget.tests_per_face)) {
        FitPieces candidate = pieces;
        join(candidate, together, *net, p);  // q's faces join p
        if (offer(candidate)) {
          pieces = std::move(candidate);
          merged = true;
          break;
        }
      }
      if (asks_left == 0 || left() < 0) break;
      failed.insert(std::move(together));
    }
    if (merged || budget.split_shares.empty()) continue;
    // No pair merges: a piece split between two of its neighbours (its faces nearest each join
    // it, at the budget's shares), the smallest pieces first.
    std::vector<int> order(members.size());
    for (std::size_t b = 0; b < order.size(); ++b) order[b] = static_cast<int>(b);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return members[a].size() < members[b].size(); });
    for (int b : order) {
      if (merged || tests_left == 0 || asks_left == 0 || left() < 0) break;
      if (fixed[b]) continue;
      std::vector<int> beside;
      for (const auto& [p, q] : pairs)
        if (p == b || q == b) beside.push_back(p == b ? q : p);
      for (std::size_t i = 0; i < beside.size() && !merged; ++i)
        for (std::size_t j = i + 1; j < beside.size() && !merged; ++j) {
          if (tests_left == 0 || asks_left == 0 || left() < 0) break;
          const int a = beside[i], c = beside[j];
          std::vector<int> key = members[a];
          key.push_back(-1);
          key.insert(key.end(), members[b].begin(), members[b].end());
          key.push_back(-1);
          key.insert(key.end(), members[c].begin(), members[c].end());
          if (failed_splits.count(key)) continue;
          for (const Split& split : splits_between(graph, pieces.net.parent, of, members, b, a, c,
                                                   budget.split_shares)) {
            std::optional<Net> to_a, to_c;
            if (!(to_a = unfold_fitting(split.faces[0], {split.trees[0]}, 0,
                                        budget.split_tests_per_face)) ||
                !(to_c = unfold_fitting(split.faces[1], {split.trees[1]}, 0,
                                        budget.split_tests_per_face)))
              continue;
            FitPieces candidate = pieces;
            join(candidate, split.faces[0], *to_a, a);
            join(candidate, split.faces[1], *to_c, c);
            if (offer(candidate)) {
              pieces = std::move(candidate);
              merged = true;
            }
            break;  // the first split that unfolds tells
          }
          if (merged) break;
          failed_splits.insert(std::move(key));
        }
    }
  }
  return pieces;
}

}  // namespace papernet
