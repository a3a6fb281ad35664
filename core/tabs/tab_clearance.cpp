// Tab clearance: changes which edges of a net are cut so that cut edges get room for a glue tab.
//
// Why moves and not tab shapes: an edge without room is almost always a near-slit, a leaf of the
// cut tree at an almost flat vertex v (or an edge of a hair, a path of cut edges from such a
// leaf). The faces around v are then all linked but across that edge, so the edge's two sides
// meet at v at the angle defect of v (a few degrees) and no tab of printable height fits between
// them. Only cutting a second edge at v opens the slit. A move therefore cuts a tree link across
// an edge at an end of the blocked edge and glues a cut edge on the cycle that link closes (an
// edge swap of the spanning tree); the side of the tree that moves is laid out again from the new
// link and must not overlap the rest. A tabu search over these moves (Clearance::run) keeps the
// net with the fewest blocked edges it has seen.
#include "core/tabs/tab_clearance.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <tuple>
#include <utility>

#include "core/mesh/angle_defects.h"
#include "core/mesh/dual_graph.h"
#include "core/tabs/internal/tab_clearance_kick.h"
#include "core/tabs/internal/tab_clearance_state.h"
#include "core/tabs/tab_clearance_report.h"
#include "core/unfold/unfold_tree.h"

namespace papernet {

namespace tab_clearance_detail {

Clearance::Clearance(const Mesh& mesh, const Net& net, const TabClearanceOptions& options)
    : mesh_(mesh), nf_(static_cast<int>(mesh.faces.size())) {
  DualGraph graph = build_dual_graph(mesh);
  vboundary_ = boundary_vertices(mesh, graph);
  adj_ = std::move(graph.neighbour);
  adj_edge_ = std::move(graph.neighbour_edge);
  shape_.resize(nf_);
  vertex_faces_.assign(mesh.vertices.size(), {});
  for (int f = 0; f < nf_; ++f) {
    shape_[f] = face_shape(mesh, f);
    for (int v : mesh.faces[f]) vertex_faces_[v].push_back(f);
  }
  pos_ = net.points;
  box_.resize(nf_);
  links_.assign(nf_, 0);
  for (int f = 0; f < nf_; ++f) {
    const int p = net.parent[f];
    if (p < 0) continue;
    for (int k = 0; k < 3; ++k)
      if (adj_[f][k] == p) {
        set_link(f, k, true);
        break;
      }
  }
  tol_ = kTabRoomOverlapTolerance * bounding_box_diagonal(mesh);
  height_ = options.min_height;
  budget_ = options.max_evaluations;
  time_limit_ = options.time_limit_seconds;
  seconds_per_blocked_ = options.seconds_per_blocked_edge;
  shapes_ = tab_shapes(options.angle_deg);
  double total = 0;
  for (const auto& t : pos_)
    for (int k = 0; k < 3; ++k) total += norm(t[(k + 1) % 3] - t[k]);
  const double mean = total / (3.0 * std::max(1, nf_));
  grid_.reset(mean > 0 && std::isfinite(mean) ? mean : 1.0);
  keep_bounds_ = options.keep_bounds;
  compound_ = options.compound_moves && !options.keep_bounds;
  bounds_ = Box2::empty();
  for (int f = 0; f < nf_; ++f) {
    box_[f] = triangle_box(pos_[f]);
    grid_.insert(f, box_[f]);
    bounds_.add(box_[f]);
  }
  blocked_.assign(3 * static_cast<std::size_t>(nf_), 0);
  for (int f = 0; f < nf_; ++f)
    for (int k = 0; k < 3; ++k)
      if (canon(f, k) == 3 * f + k && blocked(f, k)) {
        blocked_[3 * f + k] = 1;
        ++blocked_count_;
      }
  parent_.assign(nf_, -1);
  tin_.assign(nf_, 0);
  size_.assign(nf_, 1);
  is_moving_.assign(nf_, 0);
  from_.assign(nf_, -1);
  slot_.assign(nf_, 0);
  stamp_.assign(3 * static_cast<std::size_t>(nf_), 0);
  defect_ = angle_defects(mesh);
  cut_degree_.assign(mesh.vertices.size(), 0);
  for (int f = 0; f < nf_; ++f)
    for (int k = 0; k < 3; ++k)
      if (f < adj_[f][k] && !linked(f, k))
        ++cut_degree_[mesh.faces[f][k]], ++cut_degree_[mesh.faces[f][(k + 1) % 3]];
  root_tree();
}

std::vector<EdgeSide> Clearance::blocked_edges() const {
  std::vector<EdgeSide> out;
  for (int h = 0; h < 3 * nf_; ++h)
    if (blocked_[h]) out.push_back({h / 3, h % 3});
  return out;
}

bool Clearance::coincident(int f, int k) const {
  const int n = adj_[f][k], kn = adj_edge_[f][k];
  return sides_coincide(pos_[f][k], pos_[f][(k + 1) % 3], pos_[n][kn], pos_[n][(kn + 1) % 3]);
}

void Clearance::set_link(int f, int k, bool on) {
  const int n = adj_[f][k], kn = adj_edge_[f][k];
  if (on) {
    links_[f] |= static_cast<std::uint8_t>(1u << k);
    links_[n] |= static_cast<std::uint8_t>(1u << kn);
  } else {
    links_[f] &= static_cast<std::uint8_t>(~(1u << k));
    links_[n] &= static_cast<std::uint8_t>(~(1u << kn));
  }
}

void Clearance::root_tree() {
  order_.clear();
  std::vector<int> stack{0};
  parent_[0] = -1;
  while (!stack.empty()) {
    const int x = stack.back();
    stack.pop_back();
    tin_[x] = static_cast<int>(order_.size());
    order_.push_back(x);
    for (int k = 0; k < 3; ++k)
      if (linked(x, k) && adj_[x][k] != parent_[x]) {
        parent_[adj_[x][k]] = x;
        stack.push_back(adj_[x][k]);
      }
  }
  for (int i = nf_ - 1; i >= 0; --i) {
    const int x = order_[i];
    size_[x] = 1;
    for (int k = 0; k < 3; ++k)
      if (linked(x, k) && adj_[x][k] != parent_[x]) size_[x] += size_[adj_[x][k]];
  }
}

void Clearance::reroot_after_swap(int lf, int lk, int cf, int ck) {
  const int lp = adj_[lf][lk];
  const int top = parent_[lf] == lp ? lf : lp;  // the side cut off: top's subtree
  int c = cf, d = adj_[cf][ck];
  if (!in_sub(top, c)) std::swap(c, d);  // c on that side, d its new parent
  const int s = size_[top], t0 = tin_[top];
  for (int x = parent_[top]; x >= 0; x = parent_[x]) size_[x] -= s;
  // The side's pre-order from c (the same walk as root_tree's), its parents and sizes.
  block_.clear();
  std::vector<int>& stack = stack_;
  stack.assign(1, c);
  parent_[c] = d;
  while (!stack.empty()) {
    const int x = stack.back();
    stack.pop_back();
    block_.push_back(x);
    size_[x] = 1;
    for (int k = 0; k < 3; ++k)
      if (linked(x, k) && adj_[x][k] != parent_[x]) {
        parent_[adj_[x][k]] = x;
        stack.push_back(adj_[x][k]);
      }
  }
  for (std::size_t i = block_.size(); i-- > 1;) size_[parent_[block_[i]]] += size_[block_[i]];
  for (int x = d; x >= 0; x = parent_[x]) size_[x] += s;
  // The block moves to right after d in the pre-order; the faces between shift by its size.
  const int pd = tin_[d];
  int lo = 0, hi = 0, at = 0;
  if (pd < t0) {
    std::copy_backward(order_.begin() + pd + 1, order_.begin() + t0, order_.begin() + t0 + s);
    lo = at = pd + 1, hi = t0 + s;
  } else {
    std::copy(order_.begin() + t0 + s, order_.begin() + pd + 1, order_.begin() + t0);
    lo = t0, hi = pd + 1, at = pd + 1 - s;
  }
  std::copy(block_.begin(), block_.end(), order_.begin() + at);
  for (int i = lo; i < hi; ++i) tin_[order_[i]] = i;
}

void Clearance::place(int f, const Triangle2& p) {
  grid_.remove(f);
  pos_[f] = p;
  box_[f] = triangle_box(p);
  grid_.insert(f, box_[f]);
}

// Cuts the link across edge lk of face lf and glues cut edge ck of face cf and leaves the change
// applied (commit() or undo() next) when it adds no overlap and gives blocked edge tk of face tf
// room (or glues it); `out` then says how the number of blocked edges and of flat leaves would
// change. Returns false, with nothing changed, otherwise.
bool Clearance::apply_move(int tf, int tk, int lf, int lk, int cf, int ck, Change& out) {
  const int lp = adj_[lf][lk];
  const int top = parent_[lf] == lp ? lf : lp;
  const int cq = adj_[cf][ck];
  if (in_sub(top, cf) == in_sub(top, cq)) return false;  // the glue would close a cycle
  ++evaluations_;
  const bool small_is_sub = 2 * size_[top] <= nf_;
  const auto moving = [&](int x) { return in_sub(top, x) == small_is_sub; };
  const int anchor = moving(cf) ? cf : cq, fixed = anchor == cf ? cq : cf;
  const int ka = anchor == cf ? ck : adj_edge_[cf][ck], kf = anchor == cf ? adj_edge_[cf][ck] : ck;

  // Lay out the moving side again from the new link, nearest faces first, each checked at once
  // for overlap with the side that stays (and, keep_bounds, for leaving the net's box).
  const auto clashes = [&](const Triangle2& t) {
    const Box2 b = triangle_box(t);
    bool hit = keep_bounds_ && (b.lo.x < bounds_.lo.x || b.lo.y < bounds_.lo.y ||
                                b.hi.x > bounds_.hi.x || b.hi.y > bounds_.hi.y);
    grid_.query(b, [&](int c) {
      if (!hit && !moving(c)) hit = triangles_overlap(t, pos_[c], tol_);
    });
    return hit;
  };
  const auto give_up = [&] {
    for (int x : moving_) is_moving_[x] = 0;
    return false;
  };
  moving_.assign(1, anchor);
  new_pos_.assign(1, place_across(pos_[fixed], kf, ka, shape_[anchor]));
  is_moving_[anchor] = 1;
  if (clashes(new_pos_[0])) return give_up();
  for (std::size_t i = 0; i < moving_.size(); ++i) {
    const int x = moving_[i];
    for (int k = 0; k < 3; ++k) {
      const int y = adj_[x][k];
      if (!linked(x, k) || is_moving_[y]) continue;
      if ((x == lf && k == lk) || (x == lp && k == adj_edge_[lf][lk])) continue;  // the cut link
      is_moving_[y] = 1;
      moving_.push_back(y);
      new_pos_.push_back(place_across(new_pos_[i], k, adj_edge_[x][k], shape_[y]));
      if (clashes(new_pos_.back())) return give_up();
    }
  }
  // Drop it when the edge it is for would still have no room, before the moved faces change
  // places in the grid (two thirds of the moves laid out without overlap end here); else apply
  // it.
  for (std::size_t i = 0; i < moving_.size(); ++i) slot_[moving_[i]] = static_cast<int>(i);
  set_link(lf, lk, false);
  set_link(cf, ck, true);
  const Blocked before = blocked_when_moved(tf, tk);
  if (before == Blocked::kYes) {
    set_link(cf, ck, false);
    set_link(lf, lk, true);
    return give_up();
  }
  old_pos_.resize(moving_.size());
  for (std::size_t i = 0; i < moving_.size(); ++i) {
    old_pos_[i] = pos_[moving_[i]];
    place(moving_[i], new_pos_[i]);
  }
  pending_.assign(1, {lf, lk, cf, ck});
  if (before == Blocked::kUnknown && blocked(tf, tk)) {
    undo();
    return false;
  }
  recount(out);
  return true;
}

Clearance::Blocked Clearance::blocked_when_moved(int f, int k) {
  const auto at = [&](int x) -> const Triangle2& {
    return is_moving_[x] ? new_pos_[slot_[x]] : pos_[x];
  };
  const int n = adj_[f][k], kn = adj_edge_[f][k];
  if (n < 0 || linked(f, k) ||
      sides_coincide(at(f)[k], at(f)[(k + 1) % 3], at(n)[kn], at(n)[(kn + 1) % 3]))
    return Blocked::kNo;  // not a cut edge
  // The moved faces that may meet a tab on either side: a tab lies within its height of its edge.
  Box2 reach = triangle_box({at(f)[k], at(f)[(k + 1) % 3], at(n)[kn]});
  reach.add(at(n)[(kn + 1) % 3]);
  const double grow = height_ + tol_;
  reach = {{reach.lo.x - grow, reach.lo.y - grow}, {reach.hi.x + grow, reach.hi.y + grow}};
  near_.clear();
  // Beyond a few moved faces near the edge, where they are or where they go, the test after
  // the move is faster: here each goes against every tab shape one by one, and the grid still
  // holds them where they were (crowded slivers, the Twin plate).
  std::size_t were_near = 0;
  for (std::size_t i = 0; i < moving_.size(); ++i) {
    if (boxes_overlap(reach, box_[moving_[i]], 0) && ++were_near > kNearMovedFaces)
      return Blocked::kUnknown;
    if (boxes_overlap(reach, triangle_box(new_pos_[i]), 0)) {
      if (near_.size() == kNearMovedFaces) return Blocked::kUnknown;
      near_.push_back(static_cast<int>(i));
    }
  }
  // side_has_room with the moved faces where the move puts them.
  const auto room = [&](int x, int j) {
    return room_beside(
        at(x), j, [&](int c) { return is_moving_[c] != 0; },
        [&](const Triangle2& t0, const Triangle2& t1, const Box2& box) {
          for (int i : near_) {
            const Triangle2& q = new_pos_[i];
            if (boxes_overlap(box, triangle_box(q), tol_) &&
                (triangles_overlap(t0, q, tol_) || triangles_overlap(t1, q, tol_)))
              return true;
          }
          return false;
        });
  };
  return !room(f, k) && !room(n, kn) ? Blocked::kYes : Blocked::kNo;
}

// Makes the swaps together (each cuts link lk of face lf and glues cut edge ck of face cf) and
// leaves them applied, like apply_move, when they leave a spanning tree whose net has no
// overlap and gives blocked edge tk of face tf room; only the end result is checked, so a
// swap that would overlap alone may be made with one that moves the clashing faces away.
// Faces whose way to face `root` crosses a new link are laid out again; the others stay
// exactly (so `root` is best a face on the larger side of both swaps).
bool Clearance::apply_compound(int tf, int tk, const std::vector<std::array<int, 4>>& swaps,
                               int root, Change& out) {
  ++evaluations_;
  pending_ = swaps;
  for (const auto& [lf, lk, cf, ck] : swaps) {
    set_link(lf, lk, false);
    set_link(cf, ck, true);
  }
  const auto revert = [&] {
    for (auto it = swaps.rbegin(); it != swaps.rend(); ++it) {
      set_link((*it)[2], (*it)[3], false);
      set_link((*it)[0], (*it)[1], true);
    }
    return false;
  };
  const auto give_up = [&] {
    for (int x : moving_) is_moving_[x] = 0;
    return revert();
  };
  // What the swaps change, taken together: links of the current tree cut (tops_, each the face
  // below its link) and cut edges glued (glues_). A link cut and glued again by a later swap,
  // or glued and cut again, changes nothing.
  tops_.clear();
  glues_.clear();
  const auto tree_link = [&](int x, int j) {
    const int y = adj_[x][j];
    return y >= 0 && (parent_[x] == y || parent_[y] == x);
  };
  for (const auto& [lf, lk, cf, ck] : swaps) {
    if (tree_link(lf, lk) && !linked(lf, lk)) {
      const int top = parent_[lf] == adj_[lf][lk] ? lf : adj_[lf][lk];
      if (std::find(tops_.begin(), tops_.end(), top) == tops_.end()) tops_.push_back(top);
    }
    if (adj_[cf][ck] >= 0 && !tree_link(cf, ck) && linked(cf, ck)) {
      const std::pair<int, int> g{std::min(cf, adj_[cf][ck]),
                                  cf < adj_[cf][ck] ? ck : adj_edge_[cf][ck]};
      if (std::find(glues_.begin(), glues_.end(), g) == glues_.end()) glues_.push_back(g);
    }
  }
  // Without the cut links the tree falls into parts (part_of); the links are a spanning tree
  // again when the glued edges join those parts without a cycle.
  const int n = static_cast<int>(tops_.size());
  if (n == 0 || glues_.size() != tops_.size()) return revert();
  std::vector<int> joined(n + 1);  // union-find over the parts
  for (int i = 0; i <= n; ++i) joined[i] = i;
  const auto set_of = [&](int i) {
    while (joined[i] != i) i = joined[i] = joined[joined[i]];
    return i;
  };
  for (const auto& [x, j] : glues_) {
    const int a = set_of(part_of(tops_.data(), n, x)),
              b = set_of(part_of(tops_.data(), n, adj_[x][j]));
    if (a == b) return revert();  // a cycle
    joined[a] = b;
  }
  // The faces whose way to `root` crosses a glued edge move: the parts other than root's, laid
  // out from the edges glued to root's part on, breadth first.
  const int root_part = part_of(tops_.data(), n, root);
  moving_.clear();
  new_pos_.clear();
  for (const auto& [x, j] : glues_)
    for (const auto& [a, b, k] : {std::tuple{x, adj_[x][j], adj_edge_[x][j]},
                                  std::tuple{adj_[x][j], x, static_cast<std::int8_t>(j)}})
      if (part_of(tops_.data(), n, a) == root_part && part_of(tops_.data(), n, b) != root_part) {
        from_[b] = k;
        is_moving_[b] = 1;
        moving_.push_back(b);
      }
  for (std::size_t i = 0; i < moving_.size(); ++i) {
    const int x = moving_[i];
    for (int k = 0; k < 3; ++k) {
      if (!linked(x, k)) continue;
      const int y = adj_[x][k];
      if (y == adj_[x][from_[x]]) continue;  // its parent
      from_[y] = adj_edge_[x][k];
      is_moving_[y] = 1;
      moving_.push_back(y);
    }
  }
  if (moving_.empty()) return give_up();
  // Lay out the moved faces (parents first), each checked at once against the faces that stay
  // (most candidates fail here, early); then, when the swaps moved parts differently, each
  // against the moved ones placed before it.
  for (int y : moving_) {
    const int p = adj_[y][from_[y]], kp = adj_edge_[y][from_[y]];
    slot_[y] = static_cast<int>(new_pos_.size());
    new_pos_.push_back(
        place_across(is_moving_[p] ? new_pos_[slot_[p]] : pos_[p], kp, from_[y], shape_[y]));
    const Triangle2& t = new_pos_.back();
    bool hit = false;
    grid_.query(triangle_box(t), [&](int c) {
      if (!hit && !is_moving_[c]) hit = triangles_overlap(t, pos_[c], tol_);
    });
    if (hit) return give_up();
  }
  for (int x : moving_) grid_.remove(x);
  std::size_t placed = 0;
  bool hit = false;
  for (; placed < moving_.size(); ++placed) {
    const Triangle2& t = new_pos_[placed];
    grid_.query(triangle_box(t), [&](int c) {
      if (!hit && is_moving_[c]) hit = triangles_overlap(t, new_pos_[slot_[c]], tol_);
    });
    if (hit) break;
    grid_.insert(moving_[placed], triangle_box(t));
  }
  old_pos_.resize(moving_.size());
  for (std::size_t i = 0; i < moving_.size(); ++i) old_pos_[i] = pos_[moving_[i]];
  if (hit) {
    for (std::size_t i = 0; i < placed; ++i) grid_.remove(moving_[i]);
    for (int x : moving_) grid_.insert(x, box_[x]);
    return give_up();
  }
  for (std::size_t i = 0; i < moving_.size(); ++i) {  // the grid has them there already
    pos_[moving_[i]] = new_pos_[i];
    box_[moving_[i]] = triangle_box(new_pos_[i]);
  }
  if (blocked(tf, tk)) {
    undo();
    return false;
  }
  recount(out);
  return true;
}

// The change a move applied (pending_, moving_, old_pos_) makes to the blocked edges and the
// flat leaves; leaves affected_ and mark_ for commit().
void Clearance::recount(Change& out) {
  // Edges whose room may change: cut edges of faces near the border between the two sides,
  // before and after the move (a tab is at most height_ away from its edge).
  if (++epoch_ == 0) std::fill(stamp_.begin(), stamp_.end(), 0), epoch_ = 1;
  affected_.clear();
  const auto mark = [&](int f) {
    for (int k = 0; k < 3; ++k) {
      if (adj_[f][k] < 0) continue;
      const int h = canon(f, k);
      if (stamp_[h] != epoch_) stamp_[h] = epoch_, affected_.push_back(h);
    }
  };
  const auto near = [&](const Box2& b, int s) {
    const Box2 grown{{b.lo.x - height_, b.lo.y - height_}, {b.hi.x + height_, b.hi.y + height_}};
    grid_.query(grown, [&](int c) {
      if (is_moving_[c]) return;
      const Box2& o = box_[c];
      if (o.lo.x > grown.hi.x || o.hi.x < grown.lo.x || o.lo.y > grown.hi.y || o.hi.y < grown.lo.y)
        return;
      mark(c);
      mark(s);
    });
  };
  for (std::size_t i = 0; i < moving_.size(); ++i) {
    near(triangle_box(old_pos_[i]), moving_[i]);
    near(box_[moving_[i]], moving_[i]);
  }
  for (const auto& [lf, lk, cf, ck] : pending_) mark(lf), mark(cf);
  long long before = 0, after = 0;
  mark_.clear();
  for (int h : affected_) {
    before += blocked_[h];
    const int b = blocked(h / 3, h % 3) ? 1 : 0;
    mark_.push_back(b);
    after += b;
  }
  out.blocked = after - before;
  // Flat leaves: the cut links' ends gain a cut edge, the glued edges' ends lose one.
  ends_.clear();
  for (const auto& [lf, lk, cf, ck] : pending_) {
    for (int v : {mesh_.faces[lf][lk], mesh_.faces[lf][(lk + 1) % 3]}) ends_.push_back({v, 1});
    for (int v : {mesh_.faces[cf][ck], mesh_.faces[cf][(ck + 1) % 3]}) ends_.push_back({v, -1});
  }
  const auto flat_leaf = [&](int v, int degree) { return degree == 1 && !harmless(v); };
  out.flat_leaves = 0;
  for (std::size_t i = 0; i < ends_.size(); ++i) {
    bool seen = false;
    for (std::size_t j = 0; j < i; ++j) seen = seen || ends_[j].first == ends_[i].first;
    if (seen) continue;
    const int v = ends_[i].first;
    int degree = cut_degree_[v];
    for (const auto& [w, d] : ends_)
      if (w == v) degree += d;
    out.flat_leaves += (flat_leaf(v, degree) ? 1 : 0) - (flat_leaf(v, cut_degree_[v]) ? 1 : 0);
  }
}

void Clearance::undo() {
  for (auto it = pending_.rbegin(); it != pending_.rend(); ++it) {
    const auto [lf, lk, cf, ck] = *it;
    set_link(cf, ck, false);
    set_link(lf, lk, true);
  }
  for (std::size_t i = 0; i < moving_.size(); ++i) place(moving_[i], old_pos_[i]);
  for (int x : moving_) is_moving_[x] = 0;
}

void Clearance::commit() {
  for (int x : moving_) is_moving_[x] = 0;
  long long delta = 0;
  for (std::size_t i = 0; i < affected_.size(); ++i) {
    delta += mark_[i] - blocked_[affected_[i]];
    blocked_[affected_[i]] = static_cast<char>(mark_[i]);
  }
  blocked_count_ = static_cast<std::size_t>(static_cast<long long>(blocked_count_) + delta);
  for (const auto& [lf, lk, cf, ck] : pending_) {
    ++cut_degree_[mesh_.faces[lf][lk]], ++cut_degree_[mesh_.faces[lf][(lk + 1) % 3]];
    --cut_degree_[mesh_.faces[cf][ck]], --cut_degree_[mesh_.faces[cf][(ck + 1) % 3]];
    ++moves_;
  }
  if (pending_.size() == 1) {
    const auto [lf, lk, cf, ck] = pending_[0];
    reroot_after_swap(lf, lk, cf, ck);
  } else {
    root_tree();
  }
}
}  // namespace tab_clearance_detail

using tab_clearance_detail::Clearance;
using tab_clearance_detail::kSearchOnBlocked;
using tab_clearance_detail::PassProgress;

std::vector<EdgeSide> edges_without_tab_room(const Mesh& mesh, const Net& net,
                                             const TabClearanceOptions& options) {
  if (!(options.min_height > 0)) return {};
  return Clearance(mesh, net, options).blocked_edges();
}

TabClearanceResult clear_tab_room(const Mesh& mesh, const Net& net,
                                  const TabClearanceOptions& options, Progress& progress) {
  TabClearanceResult result;
  result.net = net;
  if (!(options.min_height > 0) || mesh.faces.empty()) return result;
  const auto start = std::chrono::steady_clock::now();
  // Less the time the caller reserves for the edges still without room.
  const auto seconds_left = [&](std::size_t blocked) {
    return options.time_limit_seconds -
           options.seconds_per_blocked_edge * static_cast<double>(blocked) -
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  // Both rounds' budget: the second is as long as the first (see below).
  const bool second = options.second_round && !options.keep_bounds;
  PassProgress pass(progress, (second ? 2 : 1) * options.max_evaluations,
                    options.time_limit_seconds, mesh.faces.size());
  Clearance state(mesh, net, options);
  // The search's clock starts now: setting up its state (every edge's room) is part of the pass.
  result.blocked_before = state.blocked_count();
  state.extend(0, seconds_left(0));
  state.run(pass);
  // The second round: when the search spent its budget with many edges left it goes on (its
  // sweeps open many edges at a time: the Duck, reference.obj); else kicks, one edge at a time
  // (docs/tabs.md, "Second round").
  const std::size_t budget = options.max_evaluations;
  result.searched_on = second && state.blocked_count() > 0 && state.evaluations_ >= budget &&
                       state.blocked_count() > kSearchOnBlocked;
  if (result.searched_on) {
    state.extend(budget, seconds_left(0));
    state.run(pass);
  }
  result.blocked_after = state.blocked_count();
  result.moves = state.moves_;
  result.evaluations = state.evaluations_;
  result.compound_moves = state.compound_moves_;
  if (result.moves > 0) result.net = state.net();
  result.blocked = state.blocked_edges();  // of result.net: the input, or the state's best
  if (second && !result.searched_on && state.blocked_count() > 0) {
    const std::size_t kicks = result.kicks;
    tab_clearance_detail::kick(mesh, options, seconds_left(state.blocked_count()), pass, result);
    if (result.kicks != kicks) result.blocked.reset();
  }
  pass.done(result.evaluations);
  return result;
}

}  // namespace papernet
