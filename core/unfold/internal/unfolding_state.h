// Private to the unfolder (core/unfold/unfolding*.cpp, tabu.cpp): the data of an Unfolding,
// which inherits it privately. Not part of the public API.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/unfold/overlap.h"
#include "core/unfold/overlap_grid.h"
#include "core/unfold/unfold_tree.h"

namespace papernet::unfolding_detail {

struct UnfoldingState {
  explicit UnfoldingState(Mesh mesh) : mesh_(std::move(mesh)) {}

  Mesh mesh_;
  std::vector<std::array<int, 3>> adj_;
  std::vector<std::array<std::int8_t, 3>> adj_edge_;
  std::vector<std::uint8_t> links_;  // bit k: the tree links f across edge k
  std::vector<FaceShape> shape_;
  std::vector<int> parent_;
  std::vector<Triangle2> pos_;
  std::vector<Box2> box_;
  OverlapGrid grid_;
  std::vector<std::vector<int>> overlaps_;  // partners of each face, in increasing order
  std::vector<int> overlapping_;            // faces with partners
  std::vector<int> overlapping_index_;      // position in overlapping_, -1 if absent
  bool overlapping_sorted_ = true;          // overlapping_ is in decreasing order
  std::size_t pair_count_ = 0;
  double tolerance_ = 0;

  // Editing state.
  std::unordered_map<std::uint64_t, int> half_edges_;  // a->b -> 3 * face + edge
  std::vector<std::vector<int>> vertex_faces_;
  std::vector<int> dirty_;  // faces whose shape, corners or parent changed since update()
  std::vector<char> is_dirty_;
  std::size_t link_bits_ = 0;  // set bits of links_ (2 (|F| - 1) for a tree; 0: recount)
  std::vector<int> part_;      // update_locally: part of each explored face
  std::vector<std::vector<int>> part_queue_;
  // update_locally, per part: union-find parent, size, next face to expand, still growing.
  std::vector<int> part_up_, part_size_;
  std::vector<std::size_t> part_head_;
  std::vector<char> part_open_;
  std::vector<std::pair<int, int>> todo_;
  std::vector<int> group_;  // update_locally: what moved together (-2 outside a call)
  std::vector<int> group_start_, group_order_;  // update_locally: moved faces by group
  std::size_t relaid_ = 0;                      // faces re-laid out by update(), ever

  // Pre-order of the tree from its root (root_at) and the cut being evaluated (cut): one side
  // is the pre-order range [cut_lo_, cut_hi_), the other its complement.
  std::vector<int> order_, tin_, size_, stack_;
  std::vector<int> rehung_;  // rehang_range: the range's faces in their new pre-order
  int root_ = 0, cut_lo_ = 0, cut_hi_ = 0, cut_other_ = -1;
  bool g_in_range_ = true, small_is_range_ = true;
  std::vector<std::pair<int, int>> crossing_;
  std::vector<std::uint32_t> seen_;
  std::uint32_t seen_epoch_ = 0;
  std::size_t tested_ = 0;  // faces tested by evaluate_move, ever
  std::vector<int> side_, path_;
  // grow_side: the side of a cut on a walk along a tree path, as ranges of side_faces_ (each
  // cut's head [x and the subtrees before the previous cut's side] and tail [those after]);
  // faces to visit, with their parent; near_faces: the faces nearest a cut.
  std::vector<int> side_faces_, near_;
  std::vector<std::array<std::size_t, 3>> side_ranges_;  // head begin, tail begin, tail end
  std::vector<std::pair<int, int>> side_stack_;
  std::vector<std::uint32_t> side_mark_, near_mark_;  // near_mark_: near_'s faces, by near_epoch_
  std::uint32_t side_epoch_ = 0, near_epoch_ = 0;
};

}  // namespace papernet::unfolding_detail
