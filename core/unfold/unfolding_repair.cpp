// Local repair: moves of small parts of the unfold tree that remove overlaps where they appeared
// (after a vertex split), before the Tabu Unfolder's global search. An overlap between faces a
// and b can only be removed by cutting a link on the tree path between them and gluing one side
// back along another edge; here only sides of a few faces are tried, so a move costs O(side),
// never O(|F|).
#include <algorithm>
#include <climits>
#include <cmath>

#include "core/unfold/unfolding.h"

namespace papernet {

namespace {

// The rigid motion taking triangle `from` onto the congruent triangle `to` (corner 0 onto corner
// 0, edge 0 along edge 0).
Rigid rigid_between(const Triangle2& from, const Triangle2& to) {
  const Vec2 o = from[1] - from[0], n = to[1] - to[0];
  const double re = n.x * o.x + n.y * o.y, im = n.y * o.x - n.x * o.y;
  const double len = std::hypot(re, im);
  return {from[0], to[0], re / len, im / len};
}

// Overlapping pairs whose tree paths are searched per round (the first ones of the list).
constexpr std::size_t kPairsPerRound = 8;
// Size of the largest moving side tried first; it grows fourfold while no move helps.
constexpr std::size_t kFirstSide = 16;
// Faces of a side, nearest the cut first, along whose edges it may be glued back.
constexpr std::size_t kGluable = 32;
// Links remembered as tabu (two per move).
constexpr std::size_t kTabuLinks = 16;

}  // namespace

std::uint32_t Unfolding::next_side_epoch() {
  if (side_mark_.size() < face_count()) side_mark_.resize(face_count(), 0);
  if (++side_epoch_ == 0) {
    std::fill(side_mark_.begin(), side_mark_.end(), 0);
    side_epoch_ = 1;
  }
  return side_epoch_;
}

// Faces reached from x over links without crossing to y, into side_ (marked with the epoch);
// false (side_ incomplete) when there are more than `limit`.
bool Unfolding::collect_side(int x, int y, std::size_t limit) {
  side_.clear();
  const std::uint32_t epoch = next_side_epoch();
  side_mark_[x] = epoch;
  side_.push_back(x);
  for (std::size_t i = 0; i < side_.size(); ++i) {
    const int z = side_[i];
    for (int k = 0; k < 3; ++k) {
      if (!(links_[z] >> k & 1)) continue;
      const int n = adj_[z][k];
      if ((z == x && n == y) || side_mark_[n] == epoch) continue;
      side_mark_[n] = epoch;
      side_.push_back(n);
      if (side_.size() > limit) return false;
    }
  }
  return true;
}

void Unfolding::tree_path(int a, int b) {
  // Ancestors of a, marked; then b's ancestors up to the first marked one (the meeting point).
  path_.clear();
  const std::uint32_t epoch = next_side_epoch();
  const std::size_t nf = face_count();
  for (int x = a; x >= 0 && path_.size() <= nf; x = parent_[x]) {
    side_mark_[x] = epoch;
    path_.push_back(x);
  }
  std::vector<int>& tail = side_;  // b .. just below the meeting point
  tail.clear();
  int x = b;
  for (; x >= 0 && side_mark_[x] != epoch && tail.size() <= nf; x = parent_[x]) tail.push_back(x);
  path_.resize(static_cast<std::size_t>(std::find(path_.begin(), path_.end(), x) - path_.begin()) +
               1);
  path_.insert(path_.end(), tail.rbegin(), tail.rend());
}

std::size_t Unfolding::repair_locally(const LocalRepairOptions& options, LocalRepairStats* stats) {
  update();
  LocalRepairStats st;
  const std::size_t max_side = std::max<std::size_t>(1, options.max_side);
  std::size_t limit = std::min(kFirstSide, max_side);

  struct Move {
    long long delta = LLONG_MAX;
    std::size_t side = 0;
    int x = -1, y = -1;  // the cut link; x is on the moving side
    int s = -1, k = -1;  // the new link: s (moving side) to its neighbour across edge k
  };
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> side;
  // Links cut or made by recent moves: they are neither glued nor cut again for a while.
  std::vector<std::pair<int, int>> tabu;
  const auto ordered = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  const auto is_tabu = [&](int a, int b) {
    return std::find(tabu.begin(), tabu.end(), ordered(a, b)) != tabu.end();
  };
  const long long rise = static_cast<long long>(options.max_rise);
  // The cuts evaluated in the current round and, for each way of gluing their side back, the count
  // change after each face tested. The pairs' tree paths share links, so a round meets many cuts
  // again; the state has not changed, so such a cut cannot give a better move (that needs a lower
  // count, or the same with a smaller side), and it is not evaluated again: only its tests are
  // counted, as many as the evaluation would have made (it stops where the recorded counts meet
  // the current best), so that the test budget runs out exactly as before.
  struct Cut {
    int x = -1, y = -1;
    bool small = false;  // the side has at most `limit` faces (else: the end of that path side)
    std::size_t side = 0, begin = 0, end = 0;  // side size; its gluings [begin, end)
  };
  std::vector<Cut> cuts;
  std::vector<std::pair<std::size_t, std::size_t>> gluings;  // counts [first, second)
  std::vector<long long> counts;
  while (pair_count_ > 0 && st.tests < options.max_tests) {
    Move best;
    cuts.clear();
    gluings.clear();
    counts.clear();
    // Evaluates every way of gluing the side x..(not y) in side_ (marked with `epoch`) back on.
    const auto evaluate_side = [&](int x, int y, std::uint32_t epoch) {
      long long crossing = 0;
      for (int t : side_)
        for (int b : overlaps_[t])
          if (side_mark_[b] != epoch) ++crossing;
      if (crossing == 0) return;
      // Glued back by any face near the cut (the first ones of the breadth-first side).
      const std::size_t gluable = std::min(side_.size(), kGluable);
      for (std::size_t i = 0; i < gluable; ++i)
        for (int k = 0, s = side_[i]; k < 3; ++k) {
          const int q = adj_[s][k];
          if (q < 0 || side_mark_[q] == epoch || (s == x && q == y) || is_tabu(s, q)) continue;
          const Triangle2 placed = place_across(pos_[q], adj_edge_[s][k], k, shape_[s]);
          const Rigid motion = rigid_between(pos_[s], placed);
          long long delta = -crossing;
          ++st.evaluations;
          const std::size_t first = counts.size();
          for (int t : side_) {
            const Triangle2 moved =
                t == s ? placed
                       : Triangle2{motion(pos_[t][0]), motion(pos_[t][1]), motion(pos_[t][2])};
            const std::uint32_t seen = next_seen_epoch();
            ++st.tests;
            const Box2 box = triangle_box(moved);
            grid_.query(box, [&](int c) {
              if (seen_[c] == seen || side_mark_[c] == epoch) return;
              seen_[c] = seen;
              // Faces in the grid have their current box: most candidates end here, without the
              // call (whose first test is the same).
              if (boxes_overlap(box, box_[c], tolerance_) &&
                  triangles_overlap_in_boxes(moved, pos_[c], tolerance_))
                ++delta;
            });
            counts.push_back(delta);
            // Only a move that lowers the count is applied: stop once this one cannot win.
            if (delta > rise || delta > best.delta ||
                (delta == best.delta && side_.size() >= best.side))
              break;
          }
          gluings.push_back({first, counts.size()});
          if (delta < best.delta || (delta == best.delta && side_.size() < best.side))
            best = {delta, side_.size(), x, y, s, k};
        }
    };

    // Evaluates the cut of link x - y (the side holding x moves) unless this round did; false when
    // that side has more than `limit` faces.
    const auto visit_cut = [&](int x, int y) {
      for (const Cut& c : cuts) {
        if (c.x != x || c.y != y) continue;
        for (std::size_t i = c.begin; i < c.end && c.small; ++i) {
          ++st.evaluations;
          for (std::size_t j = gluings[i].first; j < gluings[i].second; ++j) {
            ++st.tests;
            const long long d = counts[j];
            if (d > rise || d > best.delta || (d == best.delta && c.side >= best.side)) break;
          }
        }
        return c.small;
      }
      Cut c;
      c.x = x;
      c.y = y;
      c.small = collect_side(x, y, limit);
      c.begin = gluings.size();
      if (c.small) {
        c.side = side_.size();
        evaluate_side(x, y, side_epoch_);
      }
      c.end = gluings.size();
      if (options.reuse_cuts) cuts.push_back(c);
      return c.small;
    };

    pairs.clear();
    // The first pairs by their newer face (faces are numbered in order of addition: after a
    // split, its new faces first), however the grid found them.
    sort_overlapping();
    for (int a : overlapping_) {
      for (int b : overlaps_[a])
        if (b < a) pairs.push_back({a, b});
      if (pairs.size() >= kPairsPerRound) break;
    }
    for (const auto& [a, b] : pairs) {
      tree_path(a, b);
      const std::vector<int> path = path_;
      const std::size_t m = path.size();
      // Sides holding a grow along the path, sides holding b shrink: try both ends while small.
      for (std::size_t i = 0; i + 1 < m; ++i) {
        if (is_tabu(path[i], path[i + 1])) continue;
        if (!visit_cut(path[i], path[i + 1])) break;
      }
      for (std::size_t i = m - 1; i > 0; --i) {
        if (is_tabu(path[i], path[i - 1])) continue;
        if (!visit_cut(path[i], path[i - 1])) break;
      }
    }
    if (best.delta >= 0 || best.delta == LLONG_MAX) {
      if (limit < max_side) {
        limit = std::min(max_side, 4 * limit);
        continue;
      }
      // No move of a small side lowers the count: a few sideways (or slightly rising) moves,
      // never undone at once, may lead to one that does.
      if (st.sideways >= options.max_sideways || best.delta == LLONG_MAX || best.delta > rise)
        break;
      ++st.sideways;
    }
    limit = std::min(kFirstSide, max_side);
    ++st.moves;
    tabu.push_back(ordered(best.x, best.y));
    tabu.push_back(ordered(best.s, adj_[best.s][best.k]));
    if (tabu.size() > kTabuLinks) tabu.erase(tabu.begin(), tabu.begin() + 2);

    // Apply: x's side is cut from y and glued to q along s's edge k.
    collect_side(best.x, best.y, face_count());
    side = side_;
    const int q = adj_[best.s][best.k];
    int root = best.y;
    while (parent_[root] >= 0) root = parent_[root];
    if (std::find(side.begin(), side.end(), root) != side.end()) reroot(best.y);
    // Now x hangs from y: reverse the tree path s .. x, and hang s from q.
    int prev = q;
    for (int z = best.s;;) {
      const int next = parent_[z];
      parent_[z] = prev;
      if (z == best.x) break;
      prev = z;
      z = next;
    }
    const int kx = edge_to(best.x, best.y);
    links_[best.x] &= static_cast<std::uint8_t>(~(1u << kx));
    links_[best.y] &= static_cast<std::uint8_t>(~(1u << adj_edge_[best.x][kx]));
    links_[best.s] |= static_cast<std::uint8_t>(1u << best.k);
    links_[q] |= static_cast<std::uint8_t>(1u << adj_edge_[best.s][best.k]);
    // Lay the side out again exactly from its new parent, then test it.
    pos_[best.s] = place_across(pos_[q], adj_edge_[best.s][best.k], best.k, shape_[best.s]);
    std::vector<int>& todo = path_;
    todo.assign(1, best.s);
    while (!todo.empty()) {
      const int z = todo.back();
      todo.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int c = adj_[z][k];
        if (!(links_[z] >> k & 1) || c == parent_[z]) continue;
        pos_[c] = place_across(pos_[z], k, adj_edge_[z][k], shape_[c]);
        todo.push_back(c);
      }
    }
    test_moved(side);
  }
  st.overlaps = pair_count_;
  if (stats) *stats = st;
  return pair_count_;
}

}  // namespace papernet
