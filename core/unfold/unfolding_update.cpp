// Unfolding::update_locally: the incremental update's local path (after edits of a few faces,
// only the parts of the tree that move are laid out again and tested). update() in unfolding.cpp
// calls it and falls back to laying out everything.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/unfold/unfolding.h"

namespace papernet {

namespace {

std::string face_name(int f) { return "face " + std::to_string(f); }

// Links of a face: its three low bits. (std::popcount is a library call without -mpopcnt.)
std::size_t link_count(std::uint8_t bits) {
  return static_cast<std::size_t>((bits & 1) + (bits >> 1 & 1) + (bits >> 2 & 1));
}

}  // namespace

// update() when few faces were edited: keeps the largest unedited part of the tree in place,
// lays out the rest (into `moved`) and tests it for overlaps, in time proportional to it. False
// when it cannot (then the full update runs). \throw TopologyException as update().
bool Unfolding::update_locally(const std::vector<int>& around, std::vector<int>& moved) {
  const int nf = static_cast<int>(mesh_.faces.size());
  // Links of the faces around the edits, from their parents; the total count must stay |F| - 1.
  for (int f : around) {
    const int p = parent_[f];
    if (is_dirty_[f]) {
      if (p < -1 || p >= nf) throw TopologyException(face_name(f) + " is not in the unfold tree");
      if (p >= 0 && edge_to(f, p) < 0)
        throw TopologyException(face_name(f) + " hangs from " + face_name(p) +
                                ", which shares no edge with it");
    }
    std::uint8_t bits = 0;
    for (int k = 0; k < 3; ++k) {
      const int n = adj_[f][k];
      if (n >= 0 && (p == n || parent_[n] == f)) bits |= static_cast<std::uint8_t>(1u << k);
    }
    link_bits_ += link_count(bits);
    link_bits_ -= link_count(links_[f]);
    links_[f] = bits;
  }
  if (link_bits_ != 2 * static_cast<std::size_t>(nf - 1)) {
    link_bits_ = 0;  // the full update() recounts (and reports the fault)
    return false;
  }

  // The parts of the tree without edited faces, explored from their links to edited faces all at
  // once, one face per part and round, until all but the largest are known: that one keeps its
  // layout, so the work is proportional to what moves.
  const std::uint32_t epoch = next_side_epoch();
  if (part_.size() < static_cast<std::size_t>(nf)) part_.resize(nf);
  std::vector<std::vector<int>>& queue = part_queue_;
  std::vector<int>& up = part_up_;
  std::vector<int>& size = part_size_;
  std::vector<std::size_t>& head = part_head_;
  up.clear();
  size.clear();
  head.clear();
  const auto find = [&up](int i) {
    while (up[i] != i) i = up[i] = up[up[i]];
    return i;
  };
  std::size_t sources = 0;
  const auto label = [&](int x, int i) {
    side_mark_[x] = epoch;
    part_[x] = i;
    queue[i].push_back(x);
    ++size[find(i)];
  };
  for (int d : dirty_)
    for (int k = 0; k < 3; ++k) {
      const int n = adj_[d][k];
      if (!(links_[d] >> k & 1) || is_dirty_[n] || side_mark_[n] == epoch) continue;
      if (queue.size() <= sources) queue.emplace_back();
      queue[sources].clear();
      up.push_back(static_cast<int>(sources));
      size.push_back(0);
      head.push_back(0);
      label(n, static_cast<int>(sources++));
    }
  if (sources == 0) return false;  // every face was edited: lay everything out
  // Always grow the smallest part that is still growing: then at most about twice what moves is
  // explored.
  int kept = -1;
  std::vector<char>& open = part_open_;
  open.assign(sources, 0);
  for (;;) {
    int smallest = -1, growing = 0, largest = -1;
    std::fill(open.begin(), open.end(), 0);
    for (std::size_t i = 0; i < sources; ++i) {
      if (head[i] >= queue[i].size()) continue;
      const int r = find(static_cast<int>(i));
      open[r] = 1;
      if (smallest < 0 || size[r] < size[smallest] || (size[r] == size[smallest] && r < smallest))
        smallest = r;
    }
    for (std::size_t i = 0; i < sources; ++i) {
      if (up[i] != static_cast<int>(i)) continue;
      if (open[i])
        ++growing;
      else if (largest < 0 || size[i] > size[largest])
        largest = static_cast<int>(i);
    }
    if (growing == 0) {
      kept = largest;
      break;
    }
    if (growing == 1 && (largest < 0 || size[smallest] >= size[largest])) {
      kept = smallest;
      break;
    }
    // Expand a batch of faces of the smallest growing part, always from its first source with
    // faces left. Sources before the current one only change part when two parts meet: only
    // then does the search start again from the first.
    std::size_t i = 0;
    for (int step = 0; step < 32; ++step) {
      while (i < sources && !(head[i] < queue[i].size() && find(static_cast<int>(i)) == smallest))
        ++i;
      if (i == sources) break;
      const int x = queue[i][head[i]++];
      bool met = false;
      for (int k = 0; k < 3; ++k) {
        const int n = adj_[x][k];
        if (!(links_[x] >> k & 1) || is_dirty_[n]) continue;
        if (side_mark_[n] != epoch) {
          label(n, static_cast<int>(i));
        } else {
          const int a = find(part_[n]), b = find(static_cast<int>(i));
          if (a != b) {
            up[a] = b;
            size[b] += size[a];
            smallest = b;
            met = true;
          }
        }
      }
      if (met) i = 0;
    }
  }
  // The part of each source, final.
  for (std::size_t i = 0; i < sources; ++i)
    head[i] = static_cast<std::size_t>(find(static_cast<int>(i)));
  const auto part_of = [&](int x) { return static_cast<int>(head[part_[x]]); };
  const auto in_kept = [&](int x) {
    return !is_dirty_[x] && (side_mark_[x] != epoch || part_of(x) == kept);
  };
  std::size_t relaid = dirty_.size();
  for (std::size_t i = 0; i < sources; ++i)
    if (static_cast<int>(head[i]) != kept) relaid += queue[i].size();

  // Root the tree in the kept part (this also finds parent cycles: the walk would not end).
  int anchor = queue[kept].front();
  {
    int prev = -1;
    std::size_t steps = 0;
    for (int x = anchor; x != -1; ++steps) {
      if (steps > static_cast<std::size_t>(nf))
        throw TopologyException("the unfold tree has a cycle (parents never reach a root)");
      const int next = parent_[x];
      parent_[x] = prev;
      prev = x;
      x = next;
    }
  }

  // Lay out the edited faces and the other parts from their one link to the kept part.
  moved.clear();
  const std::uint32_t seen = next_seen_epoch();
  std::vector<std::pair<int, int>>& todo = todo_;
  for (int d : dirty_) {
    int from = -1;
    for (int k = 0; k < 3; ++k)
      if ((links_[d] >> k & 1) && in_kept(adj_[d][k])) {
        if (from >= 0)
          throw TopologyException("the unfold tree has a cycle through " + face_name(d));
        from = adj_[d][k];
      }
    if (from < 0) continue;
    const int kd = edge_to(d, from);
    pos_[d] = place_across(pos_[from], adj_edge_[d][kd], kd, shape_[d]);
    seen_[d] = seen;
    moved.push_back(d);
    todo.assign(1, {d, from});
    while (!todo.empty()) {
      const auto [x, parent] = todo.back();
      todo.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int n = adj_[x][k];
        if (!(links_[x] >> k & 1) || n == parent) continue;
        if (seen_[n] == seen || in_kept(n))
          throw TopologyException("the unfold tree has a cycle through " + face_name(n));
        seen_[n] = seen;
        pos_[n] = place_across(pos_[x], k, adj_edge_[x][k], shape_[n]);
        moved.push_back(n);
        todo.push_back({n, x});
      }
    }
  }
  if (moved.size() != relaid)
    throw TopologyException("the unfold tree is not one spanning tree (" +
                            std::to_string(relaid - moved.size()) + " faces are cut off)");

  // Test what moved. A part moved rigidly: pairs inside it stay as they are; its faces are tested
  // against everything else, the edited faces against everything.
  // group_: -1 for an edited face, the part for a face of a moved part, -2 for all others
  // (kept in place).
  if (group_.size() < static_cast<std::size_t>(nf)) group_.resize(nf, -2);
  for (int f : moved) group_[f] = is_dirty_[f] ? -1 : part_of(f);
  for (int f : moved) {
    if (grid_.contains(f)) grid_.remove(f);
    const int g = group_[f];
    for (std::size_t i = overlaps_[f].size(); i-- > 0;)
      if (g < 0 || group_[overlaps_[f][i]] != g) remove_pair(f, overlaps_[f][i]);
  }
  // The edited faces one by one, then each part as a whole: a face is queried while the grid
  // holds the kept faces and what was tested before it, but not its own part, so each pair of
  // faces that may have moved apart is tested once and the queries do not meet the own part.
  std::vector<int>& start = group_start_;
  start.assign(sources + 2, 0);
  for (int f : moved) ++start[static_cast<std::size_t>(group_[f] + 2)];
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<int>& order = group_order_;
  order.resize(moved.size());
  for (int f : moved) order[static_cast<std::size_t>(start[group_[f] + 1]++)] = f;
  // start[g + 1] is now the end of group g (g = -1: the edited faces).
  std::size_t inserted = 0;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const int f = order[i];
    box_[f] = triangle_box(pos_[f]);
    add_pairs_in_grid(f);
    if (group_[f] < 0 || i + 1 == order.size() || group_[order[i + 1]] != group_[f])
      for (; inserted <= i; ++inserted) grid_.insert(order[inserted], box_[order[inserted]]);
  }
  for (int f : moved) group_[f] = -2;
  return true;
}

}  // namespace papernet
