// Local repair: moves of small parts of the unfold tree that remove overlaps where they appeared
// (after a vertex split), before the Tabu Unfolder's global search. An overlap between faces a
// and b can only be removed by cutting a link on the tree path between them and gluing one side
// back along another edge; here only sides of a few faces are tried, so a move costs O(side),
// never O(|F|).
#include <algorithm>
#include <climits>
#include <cmath>

#include "core/random.h"
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
// Faces of a side, nearest the cut first, tested first when it is glued back, before the others
// in the order grow_side holds them: those near the cut lie near the net once glued back, and end
// a losing move sooner; the whole side breadth-first costs a search of it per cut, as before
// grow_side. Rocker-arm (20,088 faces, seeds 1-3) unfolds in 7.6, 6.2 and 10.4 s with 512; 8.1,
// 6.7 and 9.6 s with 128; 8.3, 7.2 and 10.1 s with 2,048; 9.8, 8.0 and 11.0 s with every side
// searched breadth-first anew (docs/performance.md, "Session 39").
constexpr std::size_t kTestedFirst = 512;
// Links remembered as tabu (two per move).
constexpr std::size_t kTabuLinks = 16;

// A new epoch for `marks` (one per face of `faces`): marks of earlier epochs no longer count.
std::uint32_t next_epoch(std::vector<std::uint32_t>& marks, std::uint32_t& epoch,
                         std::size_t faces) {
  if (marks.size() < faces) marks.resize(faces, 0);
  if (++epoch == 0) {
    std::fill(marks.begin(), marks.end(), 0);
    epoch = 1;
  }
  return epoch;
}

}  // namespace

std::uint32_t Unfolding::next_side_epoch() {
  return next_epoch(side_mark_, side_epoch_, face_count());
}

// The first `count` faces reached from x over links without crossing to y, breadth-first, into
// `out`, marked in `mark` with `epoch`.
void Unfolding::breadth_first_side(int x, int y, std::size_t count,
                                   std::vector<std::uint32_t>& mark, std::uint32_t epoch,
                                   std::vector<int>& out) const {
  out.assign(1, x);
  mark[x] = epoch;
  for (std::size_t i = 0; i < out.size() && out.size() < count; ++i) {
    const int z = out[i];
    for (int k = 0; k < 3 && out.size() < count; ++k) {
      const int n = adj_[z][k];
      if (!(links_[z] >> k & 1) || (z == x && n == y) || mark[n] == epoch) continue;
      mark[n] = epoch;
      out.push_back(n);
    }
  }
}

// Faces reached from x over links without crossing to y, into side_ (marked with the epoch);
// false (side_ incomplete) when there are more than `limit`.
bool Unfolding::collect_side(int x, int y, std::size_t limit) {
  breadth_first_side(x, y, limit + 1, side_mark_, next_side_epoch(), side_);
  return side_.size() <= limit;
}

// The side of the cut x - y holding x, marked with the epoch, as ranges of side_faces_ (which
// holds its faces) in side_ranges_: in the tree's pre-order from x (neighbours in edge order), the
// heads of the ranges, last first, then their tails, first first. `inner` -1: built anew; else
// the ranges hold the side of the cut inner - x (the previous cut of a walk along a tree path),
// which is the subtree at x's neighbour `inner`: only the faces around it are visited, so a walk
// visits each face of its last side once. False (the side incomplete) when the side has more
// than `limit` faces.
bool Unfolding::grow_side(int x, int y, int inner, std::size_t limit) {
  if (inner < 0) {
    next_side_epoch();
    side_faces_.clear();
    side_ranges_.clear();
  }
  const std::uint32_t epoch = side_epoch_;
  const auto add = [&](int t) {
    side_mark_[t] = epoch;
    side_faces_.push_back(t);
  };
  std::array<std::size_t, 3> range{side_faces_.size(), 0, 0};
  bool tail = false;
  add(x);
  for (int k = 0; k < 3; ++k) {
    const int n = adj_[x][k];
    if (!(links_[x] >> k & 1) || n == y) continue;
    if (n == inner) {
      range[1] = side_faces_.size();
      tail = true;
      continue;
    }
    // The subtree at n, in pre-order: each face's children pushed in reverse edge order.
    side_stack_.assign(1, {n, x});
    while (!side_stack_.empty()) {
      const auto [z, from] = side_stack_.back();
      side_stack_.pop_back();
      add(z);
      if (side_faces_.size() > limit) return false;
      for (int j = 2; j >= 0; --j) {
        const int c = adj_[z][j];
        if ((links_[z] >> j & 1) && c != from) side_stack_.push_back({c, z});
      }
    }
  }
  if (!tail) range[1] = side_faces_.size();
  range[2] = side_faces_.size();
  side_ranges_.push_back(range);
  return side_faces_.size() <= limit;
}

// The first `count` faces of the side of the cut x - y holding x, breadth-first from x, into
// near_ (marked in near_mark_ with near_epoch_).
void Unfolding::near_faces(int x, int y, std::size_t count) {
  breadth_first_side(x, y, count, near_mark_, next_epoch(near_mark_, near_epoch_, face_count()),
                     near_);
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
  // A seed: sideways moves are drawn among `level` (the moves that do not lower the count).
  const bool drawn = options.seed != 0;
  Random random(options.seed);
  std::vector<Move> level;
  // The cuts evaluated in the current round and, for each way of gluing their side back, the count
  // change after each face tested. The pairs' tree paths share links, so a round meets many cuts
  // again; the state has not changed, so such a cut cannot give a better move (that needs a lower
  // count, or the same with a smaller side), and it is not evaluated again: only its tests are
  // counted, as many as the evaluation would have made (it stops where the recorded counts meet
  // the current best), so that the test budget runs out exactly as before.
  struct Cut {
    int x = -1, y = -1;
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
    level.clear();
    // Evaluates every way of gluing the side x..(not y) (grow_side, marked with `epoch`) back on.
    const auto evaluate_side = [&](int x, int y, std::uint32_t epoch) {
      // The overlapping pairs across the cut: from the side's faces, or from the overlapping
      // faces (each pair seen from both) when they are fewer.
      long long crossing = 0;
      if (side_faces_.size() <= overlapping_.size()) {
        for (const int t : side_faces_)
          for (const int b : overlaps_[t]) crossing += side_mark_[b] != epoch;
      } else {
        for (const int a : overlapping_)
          for (const int b : overlaps_[a])
            crossing += (side_mark_[a] == epoch) != (side_mark_[b] == epoch);
        crossing /= 2;
      }
      if (crossing == 0) return;
      // Glued back by any face near the cut (the first ones breadth-first from it).
      near_faces(x, y, kTestedFirst);
      const std::size_t gluable = std::min(near_.size(), kGluable);
      for (std::size_t g = 0; g < gluable; ++g)
        for (int k = 0, s = near_[g]; k < 3; ++k) {
          const int q = adj_[s][k];
          if (q < 0 || side_mark_[q] == epoch || (s == x && q == y) || is_tabu(s, q)) continue;
          const Triangle2 placed = place_across(pos_[q], adj_edge_[s][k], k, shape_[s]);
          const Rigid motion = rigid_between(pos_[s], placed);
          long long delta = -crossing;
          ++st.evaluations;
          const std::size_t first = counts.size();
          // The faces near the cut first (nearest the rest of the net once glued back, so most
          // likely to meet it, which ends a move that cannot win sooner), then the rest.
          const std::size_t near = near_.size(), ranges = side_ranges_.size();
          std::size_t part = 0, at = 0, end = 0;  // part p: a head (p < ranges) or a tail
          const auto next_face = [&](std::size_t i) {
            if (i < near) return near_[i];
            for (;;) {
              while (at == end) {
                if (part == 2 * ranges) return -1;
                const auto& r = side_ranges_[part < ranges ? ranges - 1 - part : part - ranges];
                at = part < ranges ? r[0] : r[1];
                end = part < ranges ? r[1] : r[2];
                ++part;
              }
              const int t = side_faces_[at++];
              if (near_mark_[t] != near_epoch_) return t;
            }
          };
          for (std::size_t i = 0;; ++i) {
            const int t = next_face(i);
            if (t < 0) break;
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
            // Only a move that lowers the count is applied: stop once this one cannot win (or,
            // drawn, once it raises the count too much to be drawn).
            if (delta > rise ||
                (!drawn &&
                 (delta > best.delta || (delta == best.delta && side_faces_.size() >= best.side))))
              break;
          }
          gluings.push_back({first, counts.size()});
          if (drawn && delta >= 0 && delta <= rise)
            level.push_back({delta, side_faces_.size(), x, y, s, k});
          if (delta < best.delta || (delta == best.delta && side_faces_.size() < best.side))
            best = {delta, side_faces_.size(), x, y, s, k};
        }
    };

    // Evaluates the cut of link x - y (the side holding x moves: grow_side) unless this round did.
    const auto visit_cut = [&](int x, int y) {
      for (const Cut& c : cuts) {
        if (c.x != x || c.y != y) continue;
        if (drawn) return;  // its moves are in `level` already
        for (std::size_t i = c.begin; i < c.end; ++i) {
          ++st.evaluations;
          for (std::size_t j = gluings[i].first; j < gluings[i].second; ++j) {
            ++st.tests;
            const long long d = counts[j];
            if (d > rise || d > best.delta || (d == best.delta && c.side >= best.side)) break;
          }
        }
        return;
      }
      Cut c;
      c.x = x;
      c.y = y;
      c.begin = gluings.size();
      c.side = side_faces_.size();
      evaluate_side(x, y, side_epoch_);
      c.end = gluings.size();
      if (options.reuse_cuts || drawn) cuts.push_back(c);
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
      // Sides holding a grow along the path, sides holding b shrink: try both ends while small,
      // each side grown from the one before.
      for (std::size_t i = 0; i + 1 < m; ++i) {
        if (!grow_side(path[i], path[i + 1], i > 0 ? path[i - 1] : -1, limit)) break;
        if (!is_tabu(path[i], path[i + 1])) visit_cut(path[i], path[i + 1]);
      }
      for (std::size_t i = m - 1; i > 0; --i) {
        if (!grow_side(path[i], path[i - 1], i + 1 < m ? path[i + 1] : -1, limit)) break;
        if (!is_tabu(path[i], path[i - 1])) visit_cut(path[i], path[i - 1]);
      }
    }
    if (best.delta >= 0 || best.delta == LLONG_MAX) {
      // A walk draws among the sides of this size before it tries larger ones.
      if (limit < max_side && (!drawn || level.empty())) {
        limit = std::min(max_side, 4 * limit);
        continue;
      }
      // No move of a small side lowers the count: a few sideways (or slightly rising) moves,
      // never undone at once, may lead to one that does.
      if (drawn && !level.empty()) best = level[random.below(level.size())];
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
