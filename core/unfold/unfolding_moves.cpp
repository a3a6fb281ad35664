// The move primitives of the Tabu Unfolder. A move cuts the link between face g and its parent
// and links g to another neighbour q; it is a rigid motion of one side of the cut relative to
// the other, so only overlaps between the two sides change, and only the smaller side is moved
// and tested. The sides are ranges of the tree's pre-order, so finding them costs nothing.
#include <algorithm>
#include <cmath>

#include "core/unfold/unfolding.h"

namespace papernet {

void Unfolding::root_at(int r) {
  root_ = r;
  parent_[r] = -1;
  size_.resize(face_count());
  preorder_from(r, order_);
  for (int i = 0; i < static_cast<int>(order_.size()); ++i) tin_[order_[i]] = i;
}

void Unfolding::preorder_from(int r, std::vector<int>& out) {
  out.clear();
  stack_.assign(1, r);
  while (!stack_.empty()) {
    const int x = stack_.back();
    stack_.pop_back();
    out.push_back(x);
    for (int k = 0; k < 3; ++k)
      if (links_[x] >> k & 1) {
        const int n = adj_[x][k];
        if (n == parent_[x]) continue;
        parent_[n] = x;
        stack_.push_back(n);
      }
  }
  for (auto it = out.rbegin(); it != out.rend(); ++it) {
    const int x = *it;
    size_[x] = 1;
    for (int k = 0; k < 3; ++k)
      if ((links_[x] >> k & 1) && adj_[x][k] != parent_[x]) size_[x] += size_[adj_[x][k]];
  }
}

int Unfolding::step_towards(int g, int r) const {
  if (!in_subtree_of(g, r)) return parent_[g];
  for (int k = 0; k < 3; ++k)
    if (links_[g] >> k & 1) {
      const int c = adj_[g][k];
      if (c != parent_[g] && in_subtree_of(c, r)) return c;
    }
  return -1;  // not reached for a spanning tree
}

void Unfolding::cut(int g, int other) {
  cut_other_ = other;
  // The link is g - parent_[g] (g's side is g's pre-order range) or other - parent_[other] ==
  // g (g's side is everything outside other's range).
  g_in_range_ = other == parent_[g];
  const int top = g_in_range_ ? g : other;
  cut_lo_ = tin_[top];
  cut_hi_ = cut_lo_ + size_[top];
  small_is_range_ = 2 * static_cast<std::size_t>(size_[top]) <= face_count();
}

std::uint32_t Unfolding::next_seen_epoch() {
  if (++seen_epoch_ == 0) {
    std::fill(seen_.begin(), seen_.end(), 0);
    seen_epoch_ = 1;
  }
  return seen_epoch_;
}

int Unfolding::move_anchor(int g, int k, Triangle2& anchor_pos, Rigid& motion) const {
  const int q = adj_[g][k];
  const int kq = adj_edge_[g][k];
  // The anchor is the face of the moving side that touches the new link.
  const int a = small_is_range_ == g_in_range_ ? g : q;
  anchor_pos =
      a == g ? place_across(pos_[q], kq, k, shape_[g]) : place_across(pos_[g], k, kq, shape_[q]);
  const Vec2 o = pos_[a][1] - pos_[a][0], n = anchor_pos[1] - anchor_pos[0];
  // Rotation taking direction o to direction n: (n / o) as complex numbers, normalised.
  const double re = n.x * o.x + n.y * o.y, im = n.y * o.x - n.x * o.y;
  const double len = std::hypot(re, im);
  motion = {pos_[a][0], anchor_pos[0], re / len, im / len};
  return a;
}

template <class F>
void Unfolding::for_each_crossing(F&& f) const {
  const auto from = [&](int a) {
    for (int b : overlaps_[a])
      if (!in_small(b)) f(a, b);
  };
  const int nf = static_cast<int>(face_count());
  const std::size_t small = small_is_range_ ? static_cast<std::size_t>(cut_hi_ - cut_lo_)
                                            : face_count() - (cut_hi_ - cut_lo_);
  // Walk whichever is shorter: the overlapping faces, or the smaller side's faces.
  if (small >= overlapping_.size()) {
    for (int a : overlapping_)
      if (in_small(a)) from(a);
  } else if (small_is_range_) {
    for (int i = cut_lo_; i < cut_hi_; ++i) from(order_[i]);
  } else {
    for (int i = 0; i < cut_lo_; ++i) from(order_[i]);
    for (int i = cut_hi_; i < nf; ++i) from(order_[i]);
  }
}

long long Unfolding::crossing_pairs() const {
  long long count = 0;
  for_each_crossing([&](int, int) { ++count; });
  return count;
}

long long Unfolding::evaluate_move(int g, int k, long long crossing, long long cutoff) {
  long long delta = -crossing;
  Triangle2 anchor_pos;
  Rigid motion;
  const int anchor = move_anchor(g, k, anchor_pos, motion);
  const int nf = static_cast<int>(face_count());
  const auto test = [&](int s) {
    ++tested_;
    const Triangle2 t = s == anchor
                            ? anchor_pos
                            : Triangle2{motion(pos_[s][0]), motion(pos_[s][1]), motion(pos_[s][2])};
    const std::uint32_t epoch = next_seen_epoch();
    const Box2 box = triangle_box(t);
    grid_.query(box, [&](int c) {
      if (seen_[c] == epoch || in_small(c)) return;
      seen_[c] = epoch;
      // Faces in the grid have their current box (triangles_overlap's own first test).
      if (boxes_overlap(box, box_[c], tolerance_) &&
          triangles_overlap_in_boxes(t, pos_[c], tolerance_))
        ++delta;
    });
    return delta < cutoff;
  };
  if (small_is_range_) {
    for (int i = cut_lo_; i < cut_hi_; ++i)
      if (!test(order_[i])) return delta;
  } else {
    for (int i = 0; i < cut_lo_; ++i)
      if (!test(order_[i])) return delta;
    for (int i = cut_hi_; i < nf; ++i)
      if (!test(order_[i])) return delta;
  }
  return delta;
}

void Unfolding::apply_move(int g, int k) {
  const int q = adj_[g][k];
  const int p = cut_other_;
  const int nf = static_cast<int>(face_count());
  crossing_.clear();
  for_each_crossing([&](int a, int b) { crossing_.push_back({a, b}); });
  for (const auto& [a, b] : crossing_) remove_pair(a, b);

  Triangle2 anchor_pos;
  Rigid motion;
  const int anchor = move_anchor(g, k, anchor_pos, motion);
  // The moving side leaves the grid while it is tested: the queries meet only the other side.
  const auto move = [&](int s) {
    grid_.remove(s);
    pos_[s] = s == anchor ? anchor_pos
                          : Triangle2{motion(pos_[s][0]), motion(pos_[s][1]), motion(pos_[s][2])};
    box_[s] = triangle_box(pos_[s]);
  };
  const auto retest = [&](int s) { add_pairs_in_grid(s); };
  const auto each_small = [&](const auto& visit) {
    if (small_is_range_) {
      for (int i = cut_lo_; i < cut_hi_; ++i) visit(order_[i]);
    } else {
      for (int i = 0; i < cut_lo_; ++i) visit(order_[i]);
      for (int i = cut_hi_; i < nf; ++i) visit(order_[i]);
    }
  };
  each_small(move);
  each_small(retest);
  each_small([&](int s) { grid_.insert(s, box_[s]); });

  const int kp = edge_to(g, p);
  links_[g] &= static_cast<std::uint8_t>(~(1u << kp));
  links_[p] &= static_cast<std::uint8_t>(~(1u << adj_edge_[g][kp]));
  links_[g] |= static_cast<std::uint8_t>(1u << k);
  links_[q] |= static_cast<std::uint8_t>(1u << adj_edge_[g][k]);
  if (g_in_range_)
    move_subtree(g, q);
  else
    rehang_range(g, q);
}

// After apply_move when the moved link was g - parent_[g]: g's subtree hangs from q now; updates
// the pre-order, sizes and parents to exactly what root_at(root_) gives, in time proportional to
// the faces between the old and new place of the subtree in the pre-order.
void Unfolding::move_subtree(int g, int q) {
  // g's subtree, the pre-order range [lo, hi), now hangs from q (outside it). root_at visits a
  // face's children by decreasing edge index, each with its whole subtree: the range keeps its
  // own order and moves to just after q and q's children across higher edges.
  const int lo = tin_[g], len = size_[g], hi = lo + len;
  const int kq = adj_edge_[g][edge_to(g, q)];
  int dest = tin_[q] - (tin_[q] > lo ? len : 0) + 1;  // positions without the range
  for (int k = kq + 1; k < 3; ++k) {
    const int n = adj_[q][k];
    if (!(links_[q] >> k & 1) || n == parent_[q]) continue;
    dest += size_[n] - (in_subtree_of(n, g) ? len : 0);
  }
  for (int x = parent_[g]; x != -1; x = parent_[x]) size_[x] -= len;
  for (int x = q; x != -1; x = parent_[x]) size_[x] += len;
  parent_[g] = q;
  int from = lo, to = hi;
  if (dest < lo) {
    std::rotate(order_.begin() + dest, order_.begin() + lo, order_.begin() + hi);
    from = dest;
  } else {
    std::rotate(order_.begin() + lo, order_.begin() + hi, order_.begin() + dest + len);
    to = dest + len;
  }
  for (int i = from; i < to; ++i) tin_[order_[i]] = i;
}

// After apply_move when the moved link was p - g with parent_[p] == g (the root's side moved
// relative to the other): p's subtree, the pre-order range [cut_lo_, cut_hi_), now hangs from g
// through q, one of its faces. Updates the pre-order, sizes and parents to exactly what
// root_at(root_) gives in time proportional to the range and to the faces between its old and
// new place, instead of every face: the range is ordered again from q as root_at would, then
// moves among g's children (g's size and its ancestors' stay the same).
void Unfolding::rehang_range(int g, int q) {
  const int lo = cut_lo_, hi = cut_hi_, len = hi - lo;
  parent_[q] = g;
  preorder_from(q, rehung_);
  std::copy(rehung_.begin(), rehung_.end(), order_.begin() + lo);
  // Where the range goes, in positions without it: after g (which precedes it) and g's children
  // across higher edges than the one to q, as root_at visits them.
  const int kg = edge_to(g, q);
  int dest = tin_[g] + 1;
  for (int k = kg + 1; k < 3; ++k) {
    const int n = adj_[g][k];
    if ((links_[g] >> k & 1) && n != parent_[g]) dest += size_[n];
  }
  int from = lo, to = hi;
  if (dest < lo) {
    std::rotate(order_.begin() + dest, order_.begin() + lo, order_.begin() + hi);
    from = dest;
  } else if (dest > lo) {
    std::rotate(order_.begin() + lo, order_.begin() + hi, order_.begin() + dest + len);
    to = dest + len;
  }
  for (int i = from; i < to; ++i) tin_[order_[i]] = i;
}

void Unfolding::relayout_all() {
  int root = 0;
  while (parent_[root] != -1) root = parent_[root];
  root_at(root);
  pos_[root] = place_root(mesh_, root, shape_[root]);
  for (int x : order_)
    if (x != root) {
      const int k = edge_to(x, parent_[x]);
      pos_[x] = place_across(pos_[parent_[x]], adj_edge_[x][k], k, shape_[x]);
    }
  test_moved(order_);
}

}  // namespace papernet
