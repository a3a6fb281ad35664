#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace papernet {

/// Spatial index of a net, updated incrementally: a hierarchical hash grid over face boxes for
/// compact faces, and a dynamic bounding-box tree for faces far longer than the finest cell.
/// Grid level L has cells `cell_size * 4^L` wide; a face goes to the finest level where its box
/// covers at most a few cells. In each level cells hash into a power-of-two table of buckets
/// without keys (cells that collide share a bucket, which only adds candidates), so a query is a
/// few array lookups per non-empty level; a level where the query box covers more cells than the
/// level has faces is scanned as a list instead. Faces whose box needs a coarser level than
/// kGridLevels - 1 (slivers and huge faces: CAD meshes with faces from 1 to 10,000 units long,
/// aspect ratios up to 1e8) go into the tree instead, which returns only the faces whose boxes
/// meet the query box, each once: in a net that is one long strip of slivers, every grid cell
/// coarse enough for them would hold nearly every face, many times over.
class OverlapGrid {
 public:
  /// Empties the grid and sets its finest cell size (> 0), typically about an edge length.
  void reset(double cell_size);
  /// Inserts face f (not in the grid) with box `box`.
  void insert(int f, const Box2& box);
  /// Removes face f (in the grid).
  void remove(int f);
  bool contains(int f) const { return f < static_cast<int>(range_.size()) && range_[f].valid; }
  /// Calls visit(face) for every face whose cells meet `box`; a face may be visited more than
  /// once, and faces whose boxes do not meet `box` may be visited too (faces in the tree: only
  /// those whose boxes meet `box`, once each).
  template <class Visit>
  void query(const Box2& box, Visit&& visit) const;

 private:
  struct Range {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
    // level: grid level, kTree (slot: its leaf) or kLevels (the list of unbounded faces, slot:
    // its place in members)
    int level = 0, slot = 0;
    bool valid = false;
  };
  // A node of the bounding-box tree: a leaf holds one face, an inner node two children.
  struct Node {
    Box2 box;
    int parent = -1, left = -1, right = -1, face = -1;
  };
  struct Level {
    double inv_cell = 1;
    std::size_t mask = 0;
    std::vector<std::vector<int>> buckets;
    std::vector<int> members;
  };
  static constexpr int kLevels = 24;
  static constexpr int kGridLevels = 2;  // levels kept as hash grids; coarser faces: the tree
  static constexpr int kTree = -1;
  static std::size_t bucket(const Level& l, int x, int y) {
    const std::uint64_t h = static_cast<std::uint32_t>(x) * 0x9e3779b1u ^
                            static_cast<std::uint64_t>(static_cast<std::uint32_t>(y)) * 0x85ebca6bu;
    return static_cast<std::size_t>((h ^ (h >> 15)) & l.mask);
  }
  // floor(v / cell size), clamped to +-1e9 (NaN as before). Within the range the truncation
  // below equals std::floor and costs fewer instructions on baseline x86-64 (no SSE4.1 round);
  // it runs four times per level and query.
  static int cell(const Level& l, double v) {
    const double x = v * l.inv_cell;
    if (x >= -1e9 && x <= 1e9) {
      const int i = static_cast<int>(x);
      return i - (x < i ? 1 : 0);
    }
    const double c = std::floor(x);
    return c < -1e9 ? -1000000000 : c > 1e9 ? 1000000000 : static_cast<int>(c);
  }
  void place(int f);
  void grow(Level& l);
  int new_node();
  void tree_insert(int leaf);
  void tree_remove(int leaf);

  std::array<Level, kLevels + 1> levels_;
  std::uint32_t used_levels_ = 0;  // bit i: levels_[i] has members (queries skip the others)
  std::vector<Range> range_;
  std::vector<Node> nodes_;
  std::vector<int> free_nodes_;
  int tree_root_ = -1;
  mutable std::vector<int> stack_;
};

template <class Visit>
void OverlapGrid::query(const Box2& box, Visit&& visit) const {
  static_assert(kLevels < 32);
  for (std::uint32_t used = used_levels_; used != 0; used &= used - 1) {
    const int i = std::countr_zero(used);
    const Level& l = levels_[i];
    if (i < kLevels) {
      const int x0 = cell(l, box.lo.x), x1 = cell(l, box.hi.x), y0 = cell(l, box.lo.y),
                y1 = cell(l, box.hi.y);
      const double cells = (static_cast<double>(x1) - x0 + 1) * (static_cast<double>(y1) - y0 + 1);
      if (cells <= static_cast<double>(l.members.size()) && x1 >= x0 && y1 >= y0) {
        for (int x = x0; x <= x1; ++x)
          for (int y = y0; y <= y1; ++y)
            for (int f : l.buckets[bucket(l, x, y)]) visit(f);
        continue;
      }
    }
    for (int f : l.members) visit(f);
  }
  if (tree_root_ < 0) return;
  const auto meets = [&box](const Box2& b) {
    return b.lo.x <= box.hi.x && box.lo.x <= b.hi.x && b.lo.y <= box.hi.y && box.lo.y <= b.hi.y;
  };
  stack_.assign(1, tree_root_);
  while (!stack_.empty()) {
    const Node& n = nodes_[stack_.back()];
    stack_.pop_back();
    if (!meets(n.box)) continue;
    if (n.face >= 0) {
      visit(n.face);
    } else {
      stack_.push_back(n.left);
      stack_.push_back(n.right);
    }
  }
}

}  // namespace papernet
