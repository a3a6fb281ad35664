// The move primitives of the Tabu Unfolder. A move cuts the link between face g and its parent
// and links g to another neighbour q; it is a rigid motion of one side of the cut relative to
// the other, so only overlaps between the two sides change, and only the smaller side is laid
// out again and tested.
#include <algorithm>

#include "core/unfolding.h"

namespace papernet {

void Unfolding::prepare_cut(int g) {
  const int p = parent_[g];
  if (epoch_ > 0xfffffff0u) {
    std::fill(mark_.begin(), mark_.end(), 0);
    epoch_ = 0;
  }
  epoch_ += 2;
  const std::uint32_t a = epoch_, b = epoch_ + 1;
  side_a_.clear();
  side_b_.clear();
  stack_a_.assign(1, g);
  stack_b_.assign(1, p);
  mark_[g] = a;
  mark_[p] = b;
  // Walk both sides in turn; the side that runs out first is the smaller one, found in time
  // proportional to its size.
  const auto step = [this](std::vector<int>& stack, std::vector<int>& side, std::uint32_t own,
                           std::uint32_t other) {
    const int x = stack.back();
    stack.pop_back();
    side.push_back(x);
    for (int k = 0; k < 3; ++k)
      if (links_[x] >> k & 1) {
        const int n = adj_[x][k];
        if (mark_[n] != own && mark_[n] != other) {
          mark_[n] = own;
          stack.push_back(n);
        }
      }
  };
  for (;;) {
    if (stack_a_.empty()) {
      small_is_subtree_ = true;
      small_mark_ = a;
      small_.swap(side_a_);
      break;
    }
    step(stack_a_, side_a_, a, b);
    if (stack_b_.empty()) {
      small_is_subtree_ = false;
      small_mark_ = b;
      small_.swap(side_b_);
      break;
    }
    step(stack_b_, side_b_, b, a);
  }
  cut_face_ = g;
}

std::uint32_t Unfolding::next_seen_epoch() {
  if (++seen_epoch_ == 0) {
    std::fill(seen_.begin(), seen_.end(), 0);
    seen_epoch_ = 1;
  }
  return seen_epoch_;
}

bool Unfolding::in_cut_subtree(int q) const {
  return small_is_subtree_ ? mark_[q] == small_mark_ : mark_[q] != small_mark_;
}

void Unfolding::layout_side(int g, int k) {
  const int q = adj_[g][k];
  const int kq = adj_edge_[g][k];
  int start;
  if (small_is_subtree_) {
    start = g;
    new_pos_[g] = place_across(pos_[q], kq, k, shape_[g]);
  } else {
    start = q;
    new_pos_[q] = place_across(pos_[g], k, kq, shape_[q]);
  }
  order_.assign(1, start);
  stack_a_.assign(1, -1);  // where each face of order_ was reached from
  for (std::size_t i = 0; i < order_.size(); ++i) {
    const int x = order_[i], from = stack_a_[i];
    for (int kk = 0; kk < 3; ++kk) {
      if (!(links_[x] >> kk & 1)) continue;
      const int n = adj_[x][kk];
      if (n == from || mark_[n] != small_mark_) continue;
      new_pos_[n] = place_across(new_pos_[x], kk, adj_edge_[x][kk], shape_[n]);
      order_.push_back(n);
      stack_a_.push_back(x);
    }
  }
}

long long Unfolding::evaluate_move(int g, int k, long long cutoff) {
  long long delta = 0;
  for (int s : small_)
    for (int c : overlaps_[s])
      if (mark_[c] != small_mark_) --delta;
  layout_side(g, k);
  for (int s : order_) {
    const Triangle2& t = new_pos_[s];
    next_seen_epoch();
    grid_.query(triangle_box(t), [&](int c) {
      if (mark_[c] == small_mark_ || seen_[c] == seen_epoch_) return;
      seen_[c] = seen_epoch_;
      if (triangles_overlap(t, pos_[c], tolerance_)) ++delta;
    });
    if (delta >= cutoff) return delta;
  }
  return delta;
}

void Unfolding::apply_move(int g, int k) {
  const int q = adj_[g][k];
  const int p = parent_[g];
  layout_side(g, k);
  std::vector<int> gone;
  for (int s : small_) {
    gone.clear();
    for (int c : overlaps_[s])
      if (mark_[c] != small_mark_) gone.push_back(c);
    for (int c : gone) remove_pair(s, c);
  }
  for (int s : order_) {
    grid_.remove(s);
    pos_[s] = new_pos_[s];
    box_[s] = triangle_box(pos_[s]);
    grid_.insert(s, box_[s]);
  }
  for (int s : order_) {
    next_seen_epoch();
    grid_.query(box_[s], [&](int c) {
      if (mark_[c] == small_mark_ || seen_[c] == seen_epoch_) return;
      seen_[c] = seen_epoch_;
      if (triangles_overlap(pos_[s], pos_[c], tolerance_)) add_pair(s, c);
    });
  }
  const int kp = edge_to(g, p);
  links_[g] &= static_cast<std::uint8_t>(~(1u << kp));
  links_[p] &= static_cast<std::uint8_t>(~(1u << adj_edge_[g][kp]));
  parent_[g] = q;
  links_[g] |= static_cast<std::uint8_t>(1u << k);
  links_[q] |= static_cast<std::uint8_t>(1u << adj_edge_[g][k]);
  cut_face_ = -1;
}

}  // namespace papernet
