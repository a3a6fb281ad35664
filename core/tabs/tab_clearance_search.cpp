// Tab clearance, the search: which moves are tried for a blocked edge (Clearance::candidates)
// and the tabu search over them (Clearance::run). The state and the moves themselves are in
// core/tab_clearance.cpp.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "core/errors.h"
#include "core/tabs/internal/tab_clearance_state.h"

namespace papernet::tab_clearance_detail {

template <class Sub, class SmallFaces, class Degree, class Skip>
std::vector<std::pair<int, int>> Clearance::crossing_glues(Sub&& sub, bool sub_small,
                                                           SmallFaces&& small_faces,
                                                           std::array<int, 2> link_ends, Vec3 at,
                                                           std::size_t most, Degree&& degree,
                                                           Skip&& skip) const {
  std::vector<std::pair<double, std::pair<int, int>>> near;
  small_faces([&](int x) {  // the cut edges from face x of the smaller side
    for (int j = 0; j < 3; ++j) {
      const int y = adj_[x][j];
      if (y < 0 || linked(x, j) || sub(y) == sub_small || skip(x, j)) continue;
      const int a = mesh_.faces[x][j], b = mesh_.faces[x][(j + 1) % 3];
      const int gain_a = a == link_ends[0] || a == link_ends[1] ? 1 : 0;
      const int gain_b = b == link_ends[0] || b == link_ends[1] ? 1 : 0;
      if ((degree(a) + gain_a - 1 < 2 && !harmless(a)) ||
          (degree(b) + gain_b - 1 < 2 && !harmless(b)))
        continue;
      const Vec3 m = 0.5 * (mesh_.vertices[a] + mesh_.vertices[b]);
      near.push_back({norm(m - at), {x, j}});
    }
  });
  // Sorted by distance, then by edge: the same glues whatever order the faces came in.
  std::sort(near.begin(), near.end());
  if (near.size() > most) near.resize(most);
  std::vector<std::pair<int, int>> out;
  for (const auto& [d, g] : near) out.push_back(g);
  return out;
}

template <class Degree, class Skip>
std::vector<std::pair<int, int>> Clearance::crossing_glues(int top, std::array<int, 2> link_ends,
                                                           Vec3 at, std::size_t most,
                                                           Degree&& degree, Skip&& skip) const {
  const bool sub_small = 2 * size_[top] <= nf_;
  const int lo = tin_[top], hi = tin_[top] + size_[top];
  return crossing_glues([&](int x) { return in_sub(top, x); }, sub_small,
                        [&](auto&& f) {
                          if (sub_small) {
                            for (int i = lo; i < hi; ++i) f(order_[i]);
                          } else {
                            for (int i = 0; i < lo; ++i) f(order_[i]);
                            for (int i = hi; i < nf_; ++i) f(order_[i]);
                          }
                        },
                        link_ends, at, most, degree, skip);
}

std::vector<std::pair<int, int>> Clearance::links_at(int a) const {
  std::vector<std::pair<int, int>> out;
  for (int x : vertex_faces_[a])
    for (int j = 0; j < 3; ++j)
      if (linked(x, j) && x < adj_[x][j] &&
          (mesh_.faces[x][j] == a || mesh_.faces[x][(j + 1) % 3] == a))
        out.push_back({x, j});
  return out;
}

std::vector<std::pair<int, int>> Clearance::kick_glues(int lf, int lk, int w) const {
  const int lp = adj_[lf][lk], top = parent_[lf] == lp ? lf : lp;
  return crossing_glues(
      top, {mesh_.faces[lf][lk], mesh_.faces[lf][(lk + 1) % 3]}, mesh_.vertices[w], kKickGlues,
      [&](int x) { return cut_degree_[x]; }, [](int, int) { return false; });
}

std::vector<int> Clearance::swapped_tree(int lf, int lk, int cf, int ck) const {
  const int lp = adj_[lf][lk], top = parent_[lf] == lp ? lf : lp;
  int c = cf, d = adj_[cf][ck];
  if (!in_sub(top, c)) std::swap(c, d);
  std::vector<int> parent = parent_;
  parent[top] = -1;
  for (int prev = d, at = c; at >= 0;) {
    const int next = parent[at];
    parent[at] = prev;
    prev = at;
    at = next;
  }
  return parent;
}

// The other ends of the cut edges at vertex x.
std::vector<int> Clearance::cut_neighbours(int x) const {
  std::vector<int> out;
  for (int f : vertex_faces_[x])
    for (int j = 0; j < 3; ++j) {
      const int a = mesh_.faces[f][j], b = mesh_.faces[f][(j + 1) % 3];
      if ((a != x && b != x) || adj_[f][j] < 0 || linked(f, j)) continue;
      const int other = a == x ? b : a;
      if (std::find(out.begin(), out.end(), other) == out.end()) out.push_back(other);
    }
  return out;
}

// When edge (u, v) lies on a hair (a path of two-cut interior vertices ending at a leaf),
// the tree links across edges at the hair's vertices, from the leaf on; else none.
std::vector<std::pair<int, int>> Clearance::hair_links(int u, int v) const {
  std::vector<std::pair<int, int>> out;
  for (auto [from, at] : {std::pair{v, u}, std::pair{u, v}}) {
    // Walk away from the edge through two-cut interior vertices; a hair ends at a leaf.
    std::vector<int> path;
    for (std::size_t steps = 0; steps < kHairSteps; ++steps) {
      if (vboundary_[at] || cut_degree_[at] > 2) break;
      path.push_back(at);
      if (cut_degree_[at] == 1) break;
      const std::vector<int> next = cut_neighbours(at);
      if (next.size() != 2) break;
      const int to = next[0] == from ? next[1] : next[0];
      from = at, at = to;
    }
    if (path.empty() || cut_degree_[path.back()] != 1) continue;
    for (auto x = path.rbegin(); x != path.rend(); ++x)  // from the leaf on
      for (int f : vertex_faces_[*x])
        for (int j = 0; j < 3; ++j) {
          const int a = mesh_.faces[f][j], b = mesh_.faces[f][(j + 1) % 3];
          if ((a == *x || b == *x) && linked(f, j) && f < adj_[f][j]) out.push_back({f, j});
        }
  }
  return out;
}

// Offers the moves around blocked edge k of face f to `consider(lf, lk, cf, ck)` (cut the link
// across edge lk of face lf, glue cut edge ck of face cf), which returns true to stop: first cut
// a link across an edge at one of its ends and glue a cut edge between nearby faces (the fan of
// its ends and one ring around); then, wider, cut any link in that ring and glue a cut edge
// within two rings; then farther glues (below). Returns true when `consider` stopped it.
template <class Consider>
bool Clearance::candidates(int f, int k, Consider&& consider) {
  const int u = mesh_.faces[f][k], v = mesh_.faces[f][(k + 1) % 3];
  std::vector<int> fan;  // faces at u or v
  for (int w : {u, v})
    for (int x : vertex_faces_[w])
      if (std::find(fan.begin(), fan.end(), x) == fan.end()) fan.push_back(x);
  const auto grow = [&](std::vector<int> faces) {
    const std::size_t n = faces.size();
    for (std::size_t i = 0; i < n; ++i)
      for (int y : adj_[faces[i]])
        if (y >= 0 && std::find(faces.begin(), faces.end(), y) == faces.end()) faces.push_back(y);
    std::sort(faces.begin(), faces.end());
    return faces;
  };
  const std::vector<int> ring1 = grow(fan), ring2 = grow(ring1);
  const auto at_ends = [&](int x, int j) {
    const int a = mesh_.faces[x][j], b = mesh_.faces[x][(j + 1) % 3];
    return a == u || a == v || b == u || b == v;
  };
  const auto links_in = [&](const std::vector<int>& faces, bool ends_only) {
    std::vector<std::pair<int, int>> out;
    for (int x : faces)
      for (int j = 0; j < 3; ++j)
        if (linked(x, j) && x < adj_[x][j] && (!ends_only || at_ends(x, j)) &&
            std::binary_search(faces.begin(), faces.end(), adj_[x][j]))
          out.push_back({x, j});
    return out;
  };
  const auto cuts_in = [&](const std::vector<int>& faces) {
    std::vector<std::pair<int, int>> out;
    for (int x : faces)
      for (int j = 0; j < 3; ++j) {
        const int y = adj_[x][j];
        if (y > x && !linked(x, j) && std::binary_search(faces.begin(), faces.end(), y))
          out.push_back({x, j});
      }
    return out;
  };
  const auto try_all = [&](const std::vector<std::pair<int, int>>& cuts,
                           const std::vector<std::pair<int, int>>& glues) {
    for (const auto& [lf, lk] : cuts)
      for (const auto& [cf, ck] : glues) {
        if (evaluations_ >= std::min(budget_, step_limit_)) return false;
        if (consider(lf, lk, cf, ck)) return true;
      }
    return false;
  };
  const auto narrow_cuts = links_in(ring1, true), narrow_glues = cuts_in(ring1);
  if (try_all(narrow_cuts, narrow_glues)) return true;
  std::vector<std::pair<int, int>> wide_cuts;
  for (const auto& c : links_in(ring1, false))
    if (std::find(narrow_cuts.begin(), narrow_cuts.end(), c) == narrow_cuts.end())
      wide_cuts.push_back(c);
  std::vector<std::pair<int, int>> wide_glues;
  for (const auto& c : cuts_in(ring2))
    if (std::find(narrow_glues.begin(), narrow_glues.end(), c) == narrow_glues.end())
      wide_glues.push_back(c);
  if (try_all(narrow_cuts, wide_glues) || try_all(wide_cuts, narrow_glues) ||
      try_all(wide_cuts, wide_glues))
    return true;
  // Farther: for a link at an end, the cut edges anywhere on the cycle it closes in the cut
  // tree (one face on each side of the link), nearest first, that leave no new flat leaf of the
  // cut tree (each end keeps another cut edge, or is sharp or on the boundary): gluing those
  // cannot create a new near-slit.
  // A hair edge (both ends on a path of two-cut vertices to a leaf) also gets the links at the
  // hair's vertices from its leaf on: cutting one there and gluing a cut edge beyond the hair
  // makes the hair a path between two parts of the net, whose sides can part.
  const Vec3 mid = 0.5 * (mesh_.vertices[u] + mesh_.vertices[v]);
  std::vector<std::pair<int, int>> all_cuts = narrow_cuts;
  all_cuts.insert(all_cuts.end(), wide_cuts.begin(), wide_cuts.end());
  if (endgame_)
    for (const std::pair<int, int>& link : hair_links(u, v))
      if (std::find(all_cuts.begin(), all_cuts.end(), link) == all_cuts.end())
        all_cuts.push_back(link);
  for (const std::pair<int, int>& cut : all_cuts) {
    // Not a structured binding: the lambda below uses them, which clang 14 refuses.
    const int lf = cut.first, lk = cut.second;
    const int lp = adj_[lf][lk], top = parent_[lf] == lp ? lf : lp;
    const std::vector<std::pair<int, int>> glues = crossing_glues(
        top, {mesh_.faces[lf][lk], mesh_.faces[lf][(lk + 1) % 3]}, mid, far_glues_,
        [&](int x) { return cut_degree_[x]; }, [](int, int) { return false; });
    if (try_all({{lf, lk}}, glues)) return true;
  }
  return false;
}

// The hair blocked edge (u, v) lies on, as vertices from its flat leaf to the first vertex
// that is not a two-cut interior vertex; empty when it lies on none.
std::vector<int> Clearance::hair_path(int u, int v) const {
  // The leaf: an end of the edge, or the end of the hair the edge lies on.
  int leaf = -1;
  for (auto [from, at] : {std::pair{v, u}, std::pair{u, v}}) {
    for (std::size_t steps = 0; steps < kHairSteps && leaf < 0; ++steps) {
      if (vboundary_[at] || cut_degree_[at] > 2) break;
      if (cut_degree_[at] == 1) {
        leaf = at;
        break;
      }
      const std::vector<int> next = cut_neighbours(at);
      if (next.size() != 2) break;
      const int to = next[0] == from ? next[1] : next[0];
      from = at, at = to;
    }
    if (leaf >= 0) break;
  }
  if (leaf < 0 || harmless(leaf)) return {};
  // From the leaf through two-cut interior vertices to the first other vertex.
  std::vector<int> path{leaf};
  int from = -1, at = leaf;
  for (std::size_t steps = 0; steps < kHairSteps; ++steps) {
    const std::vector<int> next = cut_neighbours(at);
    const int to = next.size() == 1                ? next[0]
                   : next.size() == 2 && from >= 0 ? (next[0] == from ? next[1] : next[0])
                                                   : -1;
    if (to < 0) return {};
    path.push_back(to);
    if (vboundary_[to] || cut_degree_[to] != 2) return path;
    from = at, at = to;
  }
  return {};
}

// Compound moves for blocked edge k of face f on a hair from flat leaf L = x0, x1, ..., xm (xm
// the first vertex that is not a two-cut interior vertex; m = 1 when the edge is L's own): cut
// a link at L and glue the hair's last edge (xm-1, xm), so that the hair hangs from L instead,
// then cut a link at xm-1 (the new leaf; L itself when m = 1) and glue one of the
// kCompoundGlues cut edges nearest to it on the cycle that closes that leave no new flat leaf.
// The hair becomes a path between two parts of the cut tree with neither end a leaf. The two
// swaps are checked for overlap together (apply_compound): either alone may overlap. Makes the
// first one that lowers the number of blocked edges; returns whether it did.
bool Clearance::try_compound(int f, int k, Sideways* sideways) {
  const int u = mesh_.faces[f][k], v = mesh_.faces[f][(k + 1) % 3];
  const std::vector<int> path = hair_path(u, v);
  if (path.size() < 2) return false;
  const int leaf = path[0], tail = path[path.size() - 2], end = path.back();
  const auto edge_of = [&](int a, int b, bool want_linked) {
    for (int x : vertex_faces_[a])
      for (int j = 0; j < 3; ++j) {
        const int p = mesh_.faces[x][j], q = mesh_.faces[x][(j + 1) % 3];
        if (((p == a && q == b) || (p == b && q == a)) && adj_[x][j] >= 0 &&
            linked(x, j) == want_linked)
          return std::pair{x, j};
      }
    return std::pair{-1, -1};
  };
  const auto [gf, gk] = edge_of(tail, end, false);
  if (gf < 0) return false;
  if (tabu(gf, gk)) return false;
  const Vec3 at = mesh_.vertices[tail];
  for (const std::pair<int, int>& first : links_at(leaf)) {
    const int af = first.first, ak = first.second;  // not a structured binding: lambdas use them
    if (tabu(af, ak)) continue;
    const int ap = adj_[af][ak], atop = parent_[af] == ap ? af : ap;
    if (in_sub(atop, gf) == in_sub(atop, adj_[gf][gk])) continue;
    // Faces that may be the root of the compound's layout: spread over the net, outside the
    // smaller side of the first swap (the second is checked below).
    const bool a_small = 2 * size_[atop] <= nf_;
    std::array<int, kRoots> roots{};
    std::size_t nroots = 0;
    for (std::size_t i = 0; i < kRoots; ++i) {
      const int r = static_cast<int>(i * static_cast<std::size_t>(nf_) / kRoots);
      if (in_sub(atop, r) != a_small) roots[nroots++] = r;
    }
    // The tree after the first swap, for the second swap's cycle: its links, and its sides
    // through the parts of the current tree (below), which stays rooted as it is.
    set_link(af, ak, false);
    set_link(gf, gk, true);
    const auto degree = [&](int x) {
      int d = cut_degree_[x];
      for (int w : {mesh_.faces[af][ak], mesh_.faces[af][(ak + 1) % 3]}) d += w == x ? 1 : 0;
      for (int w : {tail, end}) d -= w == x ? 1 : 0;
      return d;
    };
    std::vector<std::array<int, 4>> seconds;
    std::vector<int> second_root;
    for (const auto& [bf, bk] : links_at(tail)) {
      if (tabu(bf, bk) || (bf == af && bk == ak)) continue;
      const int b0 = mesh_.faces[bf][bk], b1 = mesh_.faces[bf][(bk + 1) % 3];
      // The sides of that tree without link b: parts of the current tree without links a and b
      // (part_of), two of them joined by the glued edge; without link a alone when b is the
      // glued edge. `sub` marks the parts on the side without face 0 (which is in part 0).
      std::array<int, 2> tops{atop, -1};
      int n = 1;
      std::array<bool, 3> sub{false, true, false};
      std::array<int, 3> part_size{nf_ - size_[atop], size_[atop], 0};
      if (canon(bf, bk) != canon(gf, gk)) {
        const int bp = adj_[bf][bk];
        tops[1] = parent_[bf] == bp ? bf : bp;
        n = 2;
        const int inner = in_sub(atop, tops[1]) ? 1 : in_sub(tops[1], atop) ? 0 : -1;
        part_size[1] = size_[atop] - (inner == 1 ? size_[tops[1]] : 0);
        part_size[2] = size_[tops[1]] - (inner == 0 ? size_[atop] : 0);
        part_size[0] = nf_ - part_size[1] - part_size[2];
        const int lone = 3 - part_of(tops.data(), 2, gf) - part_of(tops.data(), 2, adj_[gf][gk]);
        for (int i = 0; i < 3; ++i) sub[i] = lone == 0 ? i != 0 : i == lone;
      }
      const auto in_sub1 = [&](int x) { return sub[part_of(tops.data(), n, x)]; };
      int sub_size = 0;
      for (int i = 0; i <= n; ++i) sub_size += sub[i] ? part_size[i] : 0;
      const bool sub_small = 2 * sub_size <= nf_;
      int root = 0;
      for (std::size_t i = 0; i < nroots; ++i)
        if (in_sub1(roots[i]) != sub_small) {
          root = roots[i];
          break;
        }
      const auto skip = [&](int x, int j) {
        return tabu(x, j) || (x == af && j == ak) || (adj_[x][j] == af && adj_edge_[x][j] == ak);
      };
      const auto small_faces = [&](auto&& f) {
        for_each_in_parts(
            tops.data(), n, [&](int part) { return sub[part] == sub_small; }, f);
      };
      for (const auto& g : crossing_glues(in_sub1, sub_small, small_faces, {b0, b1}, at,
                                          kCompoundGlues, degree, skip)) {
        seconds.push_back({bf, bk, g.first, g.second});
        second_root.push_back(root);
      }
    }
    set_link(gf, gk, false);
    set_link(af, ak, true);
    for (std::size_t i = 0; i < seconds.size(); ++i) {
      if (evaluations_ >= std::min(budget_, step_limit_)) return false;
      Change change;
      if (!apply_compound(f, k, {{af, ak, gf, gk}, seconds[i]}, second_root[i], change)) continue;
      if (change.blocked < 0) {
        commit();
        ++compound_moves_;
        return true;
      }
      if (sideways && change.blocked <= sideways->max_blocked &&
          (sideways->swaps.empty() || change.blocked < sideways->change.blocked ||
           (change.blocked == sideways->change.blocked &&
            change.flat_leaves < sideways->change.flat_leaves))) {
        sideways->change = change;
        sideways->swaps = pending_;
        sideways->root = second_root[i];
      }
      undo();
    }
  }
  return false;
}

// Tabu search over the moves of candidates(): for each blocked edge in turn, the first move
// that lowers the number of blocked edges is made at once; when there is none, the best move
// that opens the edge (fewest blocked edges, then fewest flat leaves) is made even when it closes
// others, unless it closes more than kMaxWorsening edges net or re-cuts or re-glues an edge a
// recent move changed (tabu for kTenure steps). The best net seen is kept. Each step first
// offers an edge only its first kStepCaps[0] candidates (most overlap; the easy moves elsewhere
// come first); after kStallSweeps sweeps over the blocked edges without a new best, the next cap;
// after the last, it stops. It stops too when the budget is spent.
void Clearance::run(PassProgress& progress, std::size_t evaluations_before) {
  std::vector<std::uint8_t> best_links = links_;
  std::vector<Triangle2> best_pos = pos_;
  std::vector<char> best_blocked = blocked_;
  std::vector<int> best_degree = cut_degree_;
  std::size_t best_count = blocked_count_, best_moves = moves_, best_compound = compound_moves_;
  tabu_until_.assign(3 * static_cast<std::size_t>(nf_), 0);
  step_ = 0;
  std::size_t level = 0;
  const auto start = std::chrono::steady_clock::now();
  const auto out_of_time = [&] {
    return time_limit_ > 0 &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >=
               time_limit_ - seconds_per_blocked_ * static_cast<double>(blocked_count_);
  };
  // Back to the best net seen.
  const auto back_to_best = [&] {
    links_ = best_links;
    for (int f = 0; f < nf_; ++f)
      if (pos_[f] != best_pos[f]) place(f, best_pos[f]);
    blocked_ = best_blocked;
    cut_degree_ = best_degree;
    blocked_count_ = best_count;
    moves_ = best_moves;
    compound_moves_ = best_compound;
    root_tree();
  };
  long long max_worsening = kMaxWorsening;
  int restarts = 0;        // since the last new best
  std::size_t offset = 0;  // where sweeps start (restarts start elsewhere)
  const int halves = 3 * nf_;
  for (int stall = 0; blocked_count_ > 0 && evaluations_ < budget_ && !out_of_time();) {
    if (stall >= kStallSweeps) {
      stall = 0;
      if (++level == kStepCaps.size()) {
        // Endgame: again from the best net, with more far glues per link, moves that may close
        // one more edge on every other restart and sweeps starting elsewhere, while the budget
        // lasts (few blocked edges left: each is worth a wider search).
        if (restarts == kRestarts) break;
        ++restarts;
        if (moves_ != best_moves) back_to_best();
        std::fill(tabu_until_.begin(), tabu_until_.end(), 0);
        step_ = 0;
        level = kRestartLevel;
        far_glues_ = kFarGlues << std::min(restarts, 4);
        endgame_ = true;
        max_worsening = kMaxWorsening + restarts % 2;
        offset =
            static_cast<std::size_t>(halves) * static_cast<std::size_t>(restarts) / (kRestarts + 1);
      }
    }
    const std::size_t sweep_best = best_count;
    for (int i = 0; i < halves && evaluations_ < budget_; ++i) {
      const int h = static_cast<int>((static_cast<std::size_t>(i) + offset) % halves);
      if (!blocked_[h] || (!focus_.empty() && !focus_[h])) continue;
      if (progress.cancelled()) throw CancelledException();
      progress.at(evaluations_before + evaluations_);
      if (out_of_time()) break;
      ++step_;
      step_limit_ = evaluations_ + std::min(kStepCaps[level], budget_);
      const int f = h / 3, k = h % 3;
      struct Pick {
        Change change;
        std::array<int, 4> move{-1, -1, -1, -1};
      } pick;
      pick.change.blocked = max_worsening + 1;
      bool improved = candidates(f, k, [&](int lf, int lk, int cf, int ck) {
        if (tabu(lf, lk) || tabu(cf, ck)) return false;
        Change change;
        if (!apply_move(f, k, lf, lk, cf, ck, change)) return false;
        if (change.blocked < 0) {
          commit();
          return true;
        }
        if (change.blocked < pick.change.blocked ||
            (change.blocked == pick.change.blocked &&
             change.flat_leaves < pick.change.flat_leaves)) {
          pick.change = change;
          pick.move = {lf, lk, cf, ck};
        }
        undo();
        return false;
      });
      Sideways sideways;
      sideways.max_blocked = std::min(max_worsening, pick.change.blocked);
      if (!improved && compound_ && try_compound(f, k, &sideways)) improved = true;
      if (!improved && !sideways.swaps.empty() &&
          (pick.move[0] < 0 || sideways.change.blocked < pick.change.blocked ||
           (sideways.change.blocked == pick.change.blocked &&
            sideways.change.flat_leaves < pick.change.flat_leaves))) {
        Change change;
        if (!apply_compound(f, k, sideways.swaps, sideways.root, change)) continue;
        commit();
        ++compound_moves_;
        improved = true;
      }
      if (!improved) {
        Change change;
        if (pick.move[0] < 0 ||
            !apply_move(f, k, pick.move[0], pick.move[1], pick.move[2], pick.move[3], change))
          continue;
        commit();
      }
      // Neither undo this move nor redo the one it replaced for a while.
      const std::uint32_t until = step_ + static_cast<std::uint32_t>(kTenure);
      for (const auto& [lf, lk, cf, ck] : pending_)
        tabu_until_[canon(lf, lk)] = tabu_until_[canon(cf, ck)] = until;
      if (blocked_count_ < best_count) {
        best_count = blocked_count_;
        best_links = links_;
        best_pos = pos_;
        best_blocked = blocked_;
        best_degree = cut_degree_;
        best_moves = moves_;
        best_compound = compound_moves_;
        restarts = 0;
      }
    }
    stall = best_count < sweep_best ? 0 : stall + 1;
  }
  if (moves_ != best_moves) back_to_best();
}

}  // namespace papernet::tab_clearance_detail
