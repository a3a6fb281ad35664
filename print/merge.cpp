// Pieces merged by unfolding two at a time anew (print/merge.h, merge_pieces).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <future>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <utility>

#include "core/errors.h"
#include "core/mesh/dual_graph.h"
#include "core/tabs/tab_clearance.h"
#include "core/unfold/net_metrics.h"
#include "core/unfold/tabu.h"
#include "print/fit.h"
#include "print/internal/compact.h"
#include "print/internal/number_pieces.h"
#include "print/merge.h"

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

using Clock = std::chrono::steady_clock;

// What is left of the merge's budgets when an unfolding starts.
struct Left {
  std::size_t tests = 0, evaluations = 0;
  std::optional<Clock::time_point> deadline;  // none: no time bound
};

// What unfold_fitting found and spent. A call with more of the budgets left finds the same when
// it was not cut short (no attempt bounded by what was left rather than by its share per face),
// and one with less when `tests_needed` and `evaluations_needed` are left.
struct Unfolded {
  std::optional<Net> net;
  std::size_t tests = 0, evaluations = 0;
  std::size_t tests_needed = 0, evaluations_needed = 0;
  bool cut_short = false;
};

// What every unfolding of the merge checks its net against.
struct Target {
  const Mesh& mesh;
  double scale;
  FitRoom room;
  const TabClearanceOptions& tabs;
  const MergeBudget& budget;
};

// `together`'s faces (sorted) unfolded anew as one piece that lies flat without overlap, fits
// the room (its branches hung elsewhere where it sprawls past it: print/internal/compact.h)
// and, with tabs, leaves room for a tab on every cut inside it: from each tree of
// `starts` (indices into `together`), then from the Tabu Unfolder's starts of seeds 1 to
// `tries`, each of at most `tests_per_face` tests per face, within `left`. No net when no
// unfolding does, or the faces make no single piece. Depends on nothing else, so it may run on
// another thread while the merge goes on (`progress` is only asked whether to stop).
Unfolded unfold_fitting(const Target& target, const std::vector<int>& together,
                        const std::vector<std::vector<int>>& starts, int tries,
                        std::size_t tests_per_face, const Left& left, Progress& progress) {
  Unfolded out;
  const Mesh both = mesh_of_faces(target.mesh, together);
  const auto fits = [&](const Net& net) {
    std::vector<Vec2> corners;
    for (const auto& t : net.points)
      for (Vec2 c : t) corners.push_back(target.scale * c);
    return hull_fits(convex_hull(std::move(corners)), target.room.room);
  };
  const auto seconds_left = [&] {
    return std::chrono::duration<double>(*left.deadline - Clock::now()).count();
  };
  const auto time_up = [&] { return left.deadline && seconds_left() <= 0; };
  // A time limit for a step: what is left (0: none).
  const auto limit = [&] { return left.deadline ? std::max(seconds_left(), 1e-3) : 0.0; };
  const std::size_t test_share = tests_per_face * together.size();
  const std::size_t evaluation_share = target.budget.tab_evaluations_per_face * together.size();
  const int attempts = static_cast<int>(starts.size()) + tries;
  for (int a = 0; a < attempts; ++a) {
    if (out.tests >= left.tests) {
      out.cut_short = true;
      break;
    }
    if (time_up()) break;
    out.tests_needed = std::max(out.tests_needed, out.tests + test_share);
    const bool from_start = a < static_cast<int>(starts.size());
    TabuOptions options;
    options.seed = static_cast<std::uint64_t>(from_start ? a + 1 : a + 1 - starts.size());
    options.time_limit_seconds = limit();
    if (left.tests - out.tests < test_share) out.cut_short = true;
    options.max_tests = std::min(left.tests - out.tests, test_share);
    // Rounds whose moves are all tabu test nothing: bounded too.
    options.max_iterations = target.budget.iterations_per_face * together.size();
    UnfoldResult result;
    try {
      result = from_start ? unfold_tabu_from(both, starts[a], options, progress)
                          : unfold_tabu(both, options, progress);
    } catch (const InvalidInputException&) {
      return out;  // no single piece: faces that meet at a vertex only, or a tree that overlaps
    }
    out.tests += std::min(left.tests - out.tests, std::max<std::size_t>(result.stats.tests, 1));
    if (!result.overlap_free) continue;
    if (!fits(result.net)) {
      // Lies flat but sprawls past the room: its branches hung elsewhere, nearer its middle.
      print_detail::Compacted compact = print_detail::compact_to_fit(
          both, result.net, target.scale, target.room.room,
          target.budget.compact_evaluations_per_face * together.size(), [&] {
            if (progress.cancelled()) throw CancelledException();  // as the Tabu Unfolder does
            return time_up();
          });
      if (!compact.net || !fits(*compact.net)) continue;
      result.net = std::move(*compact.net);
    }
    if (target.tabs.min_height > 0 &&
        !edges_without_tab_room(both, result.net, target.tabs).empty()) {
      if (out.evaluations >= left.evaluations) {
        out.cut_short = true;
        continue;
      }
      out.evaluations_needed = std::max(out.evaluations_needed, out.evaluations + evaluation_share);
      TabClearanceOptions clear = target.tabs;
      if (left.evaluations - out.evaluations < evaluation_share) out.cut_short = true;
      clear.max_evaluations = std::min(left.evaluations - out.evaluations, evaluation_share);
      clear.time_limit_seconds = limit();
      TabClearanceResult cleared = clear_tab_room(both, result.net, clear, progress);
      out.evaluations += std::min(left.evaluations - out.evaluations, cleared.evaluations);
      if (cleared.blocked_after > 0 || !fits(cleared.net)) continue;
      result.net = std::move(cleared.net);
    }
    out.net = std::move(result.net);
    return out;
  }
  return out;
}

// Unfoldings of the pairs after the one whose merge is being offered, made on another thread
// while `keep` lays the merge out: the merge goes on to them in that order when it is refused,
// and finds those whose pieces it leaves as they are again after a merge it makes.
class Ahead {
 public:
  struct Pair {
    std::vector<int> together;
    std::vector<std::vector<int>> starts;
  };

  // Starts unfolding `pairs` in turn, within `left`.
  Ahead(const Target& target, std::vector<Pair> pairs, const Left& left)
      : pairs_(std::move(pairs)) {
    done_ = std::async(std::launch::async, [this, &target, left] {
      for (Pair& pair : pairs_) {
        Unfolded u;
        try {
          u = unfold_fitting(target, pair.together, pair.starts, target.budget.tries,
                             target.budget.tests_per_face, left, stop_);
        } catch (const CancelledException&) {
          return;
        }
        std::lock_guard lock(mutex_);
        found_.push_back({std::move(pair), std::move(u)});
      }
    });
  }

  // Stops, and gives what was unfolded.
  std::vector<std::pair<Pair, Unfolded>> stop() {
    stop_.asked = true;
    done_.get();
    return std::move(found_);
  }

  ~Ahead() {
    stop_.asked = true;
    if (done_.valid()) done_.wait();
  }

 private:
  struct Stop : Progress {
    bool cancelled() override { return asked; }
    std::atomic<bool> asked = false;
  };
  std::vector<Pair> pairs_;
  Stop stop_;
  std::mutex mutex_;
  std::vector<std::pair<Pair, Unfolded>> found_;
  std::future<void> done_;
};

}  // namespace

FitPieces merge_pieces(const Mesh& mesh, const std::vector<int>& part, FitPieces pieces,
                       double scale, FitRoom room, const TabClearanceOptions& tabs,
                       const MergeBudget& budget, const std::function<bool(const FitPieces&)>& keep,
                       Progress* progress, int threads) {
  const auto n = static_cast<int>(mesh.faces.size());
  const DualGraph graph = build_dual_graph(mesh);
  const Target target{mesh, scale, room, tabs, budget};
  std::size_t tests_left = budget.tests;
  std::size_t evaluations_left = budget.tab_evaluations;
  std::size_t asks_left = budget.keeps;
  // Pairs that no try merged, or whose merge was not kept, as their faces (a pair's faces stay
  // the same while neither piece changes).
  std::set<std::vector<int>> failed;
  std::optional<Clock::time_point> deadline;
  if (budget.seconds > 0)
    deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(budget.seconds));
  // The time left, or 0 without a bound; below zero when the time is up.
  const auto left = [&] {
    if (!deadline) return 0.0;
    const double t = std::chrono::duration<double>(*deadline - Clock::now()).count();
    return t > 0 ? t : -1.0;
  };
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
  // The merge's own unfoldings stop when the job is cancelled.
  struct Cancel : Progress {
    explicit Cancel(Progress* job) : job(job) {}
    bool cancelled() override { return job && job->cancelled(); }
    Progress* job;
  } cancel{progress};
  const auto within_left = [&] { return Left{tests_left, evaluations_left, deadline}; };
  // An unfolding charged to the budgets: its net.
  const auto charge = [&](Unfolded u) {
    tests_left -= std::min(tests_left, u.tests);
    evaluations_left -= std::min(evaluations_left, u.evaluations);
    report();
    return std::move(u.net);
  };
  // Pairs unfolded ahead (Ahead), by their faces, with their starts.
  std::map<std::vector<int>, std::pair<std::vector<std::vector<int>>, Unfolded>> ahead;
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
    std::vector<std::vector<int>> together(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const auto [p, q] = pairs[i];
      together[i] = members[p];
      together[i].insert(together[i].end(), members[q].begin(), members[q].end());
      std::sort(together[i].begin(), together[i].end());
    }
    // Unfolded ahead for pairs that are no longer: dropped.
    const std::set<std::vector<int>> now(together.begin(), together.end());
    std::erase_if(ahead, [&](const auto& entry) { return !now.count(entry.first); });
    // First from the two pieces' own trees glued across an edge they share (most merges need only
    // a few moves from there), then from the Tabu Unfolder's own starts.
    const auto starts = [&](std::size_t i) {
      return glued_trees(graph, pieces.net.parent, of, together[i], pairs[i].first, pairs[i].second,
                         budget.glued);
    };
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (failed.count(together[i])) continue;
      std::vector<std::vector<int>> from = starts(i);
      Unfolded unfolded;
      // Unfolded ahead from the same starts, with no less left than this needs: what it finds.
      if (const auto it = ahead.find(together[i]);
          it != ahead.end() && it->second.first == from && !it->second.second.cut_short &&
          tests_left >= it->second.second.tests_needed &&
          evaluations_left >= it->second.second.evaluations_needed)
        unfolded = std::move(it->second.second);
      else
        unfolded = unfold_fitting(target, together[i], from, budget.tries, budget.tests_per_face,
                                  within_left(), cancel);
      ahead.erase(together[i]);
      if (const std::optional<Net> net = charge(std::move(unfolded))) {
        FitPieces candidate = pieces;
        join(candidate, together[i], *net, pairs[i].first);  // q's faces join p
        // While `keep` lays the merge out, the next pairs are unfolded on another thread.
        std::optional<Ahead> next;
        if (keep && threads > 1) {
          std::vector<Ahead::Pair> after;
          for (std::size_t j = i + 1; j < pairs.size(); ++j)
            if (!failed.count(together[j]) && !ahead.count(together[j]))
              after.push_back({together[j], starts(j)});
          if (!after.empty()) next.emplace(target, std::move(after), within_left());
        }
        const bool kept = offer(candidate);
        if (next)
          for (auto& [pair, found] : next->stop())
            ahead[std::move(pair.together)] = {std::move(pair.starts), std::move(found)};
        if (kept) {
          pieces = std::move(candidate);
          merged = true;
          break;
        }
      }
      if (asks_left == 0 || left() < 0) break;
      failed.insert(together[i]);
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
            if (!(to_a =
                      charge(unfold_fitting(target, split.faces[0], {split.trees[0]}, 0,
                                            budget.split_tests_per_face, within_left(), cancel))) ||
                !(to_c =
                      charge(unfold_fitting(target, split.faces[1], {split.trees[1]}, 0,
                                            budget.split_tests_per_face, within_left(), cancel))))
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
