#include "core/unfold/overlap_grid.h"

#include <algorithm>

namespace papernet {

namespace {

// Largest number of cells a face may cover in its level.
constexpr double kMaxCells = 16;

Box2 merged(Box2 a, const Box2& b) {
  a.add(b);
  return a;
}

// Half the perimeter: the cost of a tree node (the chance that a random query meets it).
double half_perimeter(const Box2& b) { return (b.hi.x - b.lo.x) + (b.hi.y - b.lo.y); }

}  // namespace

void OverlapGrid::reset(double cell_size) {
  double inv = 1.0 / cell_size;
  for (Level& l : levels_) {
    l.inv_cell = inv;
    l.buckets.clear();
    l.mask = 0;
    l.members.clear();
    inv *= 0.25;
  }
  used_levels_ = 0;
  range_.clear();
  nodes_.clear();
  free_nodes_.clear();
  tree_root_ = -1;
}

int OverlapGrid::new_node() {
  if (!free_nodes_.empty()) {
    const int i = free_nodes_.back();
    free_nodes_.pop_back();
    nodes_[i] = Node{};
    return i;
  }
  nodes_.emplace_back();
  return static_cast<int>(nodes_.size()) - 1;
}

// Inserts a leaf next to the sibling that enlarges the tree least (the branch-and-bound descent
// of dynamic bounding-volume trees), then refits the boxes above it.
void OverlapGrid::tree_insert(int leaf) {
  if (tree_root_ < 0) {
    tree_root_ = leaf;
    nodes_[leaf].parent = -1;
    return;
  }
  const Box2 box = nodes_[leaf].box;
  int i = tree_root_;
  while (nodes_[i].face < 0) {
    const Node& n = nodes_[i];
    const double area = half_perimeter(n.box);
    const double combined = half_perimeter(merged(n.box, box));
    const double here = 2 * combined;  // a new parent of n and the leaf
    const double inherited = 2 * (combined - area);
    const auto descend = [&](int c) {
      const double grown = half_perimeter(merged(nodes_[c].box, box));
      return (nodes_[c].face >= 0 ? grown : grown - half_perimeter(nodes_[c].box)) + inherited;
    };
    const double left = descend(n.left), right = descend(n.right);
    if (here < left && here < right) break;
    i = left < right ? n.left : n.right;
  }
  const int sibling = i;
  const int old_parent = nodes_[sibling].parent;
  const int p = new_node();  // may reallocate nodes_: no references kept across it
  nodes_[p].parent = old_parent;
  nodes_[p].box = merged(nodes_[sibling].box, box);
  nodes_[p].left = sibling;
  nodes_[p].right = leaf;
  nodes_[sibling].parent = p;
  nodes_[leaf].parent = p;
  if (old_parent < 0) {
    tree_root_ = p;
  } else {
    Node& op = nodes_[old_parent];
    (op.left == sibling ? op.left : op.right) = p;
  }
  for (int a = old_parent; a >= 0; a = nodes_[a].parent)
    nodes_[a].box = merged(nodes_[nodes_[a].left].box, nodes_[nodes_[a].right].box);
}

void OverlapGrid::tree_remove(int leaf) {
  const int p = nodes_[leaf].parent;
  free_nodes_.push_back(leaf);
  if (p < 0) {
    tree_root_ = -1;
    return;
  }
  const int sibling = nodes_[p].left == leaf ? nodes_[p].right : nodes_[p].left;
  const int gp = nodes_[p].parent;
  nodes_[sibling].parent = gp;
  free_nodes_.push_back(p);
  if (gp < 0) {
    tree_root_ = sibling;
    return;
  }
  Node& g = nodes_[gp];
  (g.left == p ? g.left : g.right) = sibling;
  for (int a = gp; a >= 0; a = nodes_[a].parent)
    nodes_[a].box = merged(nodes_[nodes_[a].left].box, nodes_[nodes_[a].right].box);
}

void OverlapGrid::place(int f) {
  const Range& r = range_[f];
  Level& l = levels_[r.level];
  for (int x = r.x0; x <= r.x1; ++x)
    for (int y = r.y0; y <= r.y1; ++y) l.buckets[bucket(l, x, y)].push_back(f);
}

void OverlapGrid::grow(Level& l) {
  l.buckets.assign(std::max<std::size_t>(64, 2 * l.buckets.size()), {});
  l.mask = l.buckets.size() - 1;
  for (int f : l.members) place(f);
}

void OverlapGrid::insert(int f, const Box2& box) {
  if (f >= static_cast<int>(range_.size())) range_.resize(f + 1);
  Range& r = range_[f];
  r.valid = true;
  r.level = kLevels;
  for (int i = 0; i < kLevels; ++i) {
    const Level& l = levels_[i];
    const int x0 = cell(l, box.lo.x), x1 = cell(l, box.hi.x), y0 = cell(l, box.lo.y),
              y1 = cell(l, box.hi.y);
    if (x1 < x0 || y1 < y0) break;  // not a number
    const double cells = (static_cast<double>(x1) - x0 + 1) * (static_cast<double>(y1) - y0 + 1);
    if (cells <= kMaxCells) {
      r.x0 = x0, r.x1 = x1, r.y0 = y0, r.y1 = y1, r.level = i;
      break;
    }
    if (i + 1 == kGridLevels && std::isfinite(box.hi.x - box.lo.x) &&
        std::isfinite(box.hi.y - box.lo.y) && std::abs(box.lo.x) < 1e300 &&
        std::abs(box.lo.y) < 1e300) {
      r.level = kTree;
      r.slot = new_node();
      nodes_[r.slot].box = box;
      nodes_[r.slot].face = f;
      tree_insert(r.slot);
      return;
    }
  }
  Level& l = levels_[r.level];
  r.slot = static_cast<int>(l.members.size());
  l.members.push_back(f);
  used_levels_ |= 1u << r.level;
  if (r.level == kLevels) return;
  if (4 * l.members.size() > l.buckets.size())
    grow(l);  // grow() places f too
  else
    place(f);
}

void OverlapGrid::remove(int f) {
  Range& r = range_[f];
  if (r.level == kTree) {
    tree_remove(r.slot);
    r.valid = false;
    return;
  }
  Level& l = levels_[r.level];
  range_[l.members.back()].slot = r.slot;
  l.members[r.slot] = l.members.back();
  l.members.pop_back();
  if (l.members.empty()) used_levels_ &= ~(1u << r.level);
  if (r.level < kLevels)
    for (int x = r.x0; x <= r.x1; ++x)
      for (int y = r.y0; y <= r.y1; ++y) {
        std::vector<int>& v = l.buckets[bucket(l, x, y)];
        const auto it = std::find(v.begin(), v.end(), f);
        *it = v.back();
        v.pop_back();
      }
  r.valid = false;
}

}  // namespace papernet
