// Unfolding: construction, editing for uncollapse steps, and the incremental update (its local
// path, update_locally, is in unfolding_update.cpp). The move primitives of the Tabu Unfolder are
// in unfolding_moves.cpp, its loop in tabu.cpp.
#include "core/unfold/unfolding.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "core/errors.h"
#include "core/mesh/dual_graph.h"

namespace papernet {

namespace {

std::string face_name(int f) { return "face " + std::to_string(f); }

FaceShape checked_shape(const Mesh& mesh, int f) {
  const FaceShape s = face_shape(mesh, f);
  for (int k = 0; k < 3; ++k)
    if (!(s.left[k] > 0) || !std::isfinite(s.left[k]) || !std::isfinite(s.along[k]))
      throw InvalidInputException(face_name(f) + " is degenerate (zero area or not finite)");
  return s;
}

}  // namespace

Unfolding::Unfolding(Mesh mesh, const std::vector<int>& parent) : UnfoldingState(std::move(mesh)) {
  const int nf = static_cast<int>(mesh_.faces.size());
  if (nf == 0) throw InvalidInputException("the mesh has no faces");
  if (static_cast<int>(parent.size()) != nf)
    throw TopologyException("the unfold tree has " + std::to_string(parent.size()) +
                            " entries for " + std::to_string(nf) + " faces");
  DualGraph graph = build_dual_graph(mesh_);
  adj_ = std::move(graph.neighbour);
  adj_edge_ = std::move(graph.neighbour_edge);
  half_edges_.reserve(3 * nf);
  vertex_faces_.assign(mesh_.vertices.size(), {});
  shape_.resize(nf);
  for (int f = 0; f < nf; ++f) {
    const auto& c = mesh_.faces[f];
    for (int k = 0; k < 3; ++k) {
      half_edges_[half_edge_key(c[k], c[(k + 1) % 3])] = 3 * f + k;
      vertex_faces_[c[k]].push_back(f);
    }
    shape_[f] = checked_shape(mesh_, f);
  }
  parent_ = parent;
  links_.assign(nf, 0);
  pos_.resize(nf);
  box_.resize(nf);
  overlaps_.assign(nf, {});
  overlapping_index_.assign(nf, -1);
  tin_.assign(nf, 0);
  seen_.assign(nf, 0);
  is_dirty_.assign(nf, 0);
  tolerance_ = kOverlapTolerance * bounding_box_diagonal(mesh_);

  // The finest grid cell is the median edge length: robust to a few huge faces (coarser levels
  // of the grid take those).
  const double median = median_edge_length(mesh_);
  grid_.reset(median > 0 && std::isfinite(median) ? median : 1.0);

  // Everything is "dirty": update() checks the tree, lays out all faces and finds all overlaps.
  for (int f = 0; f < nf; ++f) {
    dirty_.push_back(f);
    is_dirty_[f] = 1;
  }
  update();
}

Unfolding Unfolding::steepest_edge(Mesh mesh, std::uint64_t seed) {
  const DualGraph graph = build_dual_graph(mesh);
  std::vector<int> parent = steepest_edge_tree(mesh, graph, seed);
  return Unfolding(std::move(mesh), parent);
}

int Unfolding::edge_to(int f, int other) const {
  for (int k = 0; k < 3; ++k)
    if (adj_[f][k] == other) return k;
  return -1;
}

void Unfolding::reroot(int r) {
  int prev = -1;
  for (int x = r; x != -1;) {
    const int next = parent_[x];
    parent_[x] = prev;
    prev = x;
    x = next;
  }
}

void Unfolding::add_pair(int a, int b) {
  for (int f : {a, b}) {
    if (overlaps_[f].empty()) {
      overlapping_index_[f] = static_cast<int>(overlapping_.size());
      overlapping_.push_back(f);
      overlapping_sorted_ = false;
    }
  }
  // Partner lists stay sorted: which partner a walk takes must not depend on the order in which
  // the spatial index reported the pairs.
  for (const auto& [f, other] : {std::pair{a, b}, std::pair{b, a}}) {
    auto& v = overlaps_[f];
    v.insert(std::lower_bound(v.begin(), v.end(), other), other);
  }
  ++pair_count_;
}

void Unfolding::remove_pair(int a, int b) {
  const auto erase = [this](int f, int other) {
    auto& v = overlaps_[f];
    v.erase(std::lower_bound(v.begin(), v.end(), other));
    if (v.empty()) {
      const int i = overlapping_index_[f];
      overlapping_[i] = overlapping_.back();
      overlapping_index_[overlapping_[i]] = i;
      overlapping_.pop_back();
      overlapping_index_[f] = -1;
      overlapping_sorted_ = overlapping_sorted_ && i == static_cast<int>(overlapping_.size());
    }
  };
  erase(a, b);
  erase(b, a);
  --pair_count_;
}

// Sorts overlapping_ by face, newest (highest) first: the random choices of the Tabu Unfolder
// and the local repair read it in this order, so that they do not depend on the order in which
// pairs were found.
void Unfolding::sort_overlapping() {
  if (overlapping_sorted_) return;
  std::sort(overlapping_.begin(), overlapping_.end(), std::greater<>());
  for (std::size_t i = 0; i < overlapping_.size(); ++i)
    overlapping_index_[overlapping_[i]] = static_cast<int>(i);
  overlapping_sorted_ = true;
}

void Unfolding::add_pairs_in_grid(int f) {
  const std::uint32_t epoch = next_seen_epoch();
  grid_.query(box_[f], [&](int c) {
    if (seen_[c] == epoch) return;
    seen_[c] = epoch;
    // Faces in the grid have their current box: most candidates end here, without the call.
    if (boxes_overlap(box_[f], box_[c], tolerance_) &&
        triangles_overlap_in_boxes(pos_[f], pos_[c], tolerance_))
      add_pair(f, c);
  });
}

void Unfolding::test_moved(const std::vector<int>& moved) {
  for (int f : moved) {
    if (grid_.contains(f)) grid_.remove(f);
    while (!overlaps_[f].empty()) remove_pair(f, overlaps_[f].back());
  }
  for (int f : moved) {
    box_[f] = triangle_box(pos_[f]);
    add_pairs_in_grid(f);
    grid_.insert(f, box_[f]);
  }
}

// ---- Editing ----

int Unfolding::add_vertex(Vec3 position) {
  mesh_.vertices.push_back(position);
  vertex_faces_.emplace_back();
  return static_cast<int>(mesh_.vertices.size()) - 1;
}

void Unfolding::set_vertex_position(int v, Vec3 position) {
  mesh_.vertices.at(v) = position;
  for (int f : vertex_faces_[v])
    if (!is_dirty_[f]) {
      is_dirty_[f] = 1;
      dirty_.push_back(f);
    }
}

void Unfolding::set_face_corners(int f, std::array<int, 3> corners) {
  auto& c = mesh_.faces.at(f);
  for (int v : corners)
    if (v < 0 || v >= static_cast<int>(mesh_.vertices.size()))
      throw TopologyException(face_name(f) + " gets vertex " + std::to_string(v) +
                              ", which does not exist");
  for (int k = 0; k < 3; ++k) {
    const auto it = half_edges_.find(half_edge_key(c[k], c[(k + 1) % 3]));
    if (it != half_edges_.end() && it->second == 3 * f + k) half_edges_.erase(it);
    auto& vf = vertex_faces_[c[k]];
    vf.erase(std::find(vf.begin(), vf.end(), f));
    // A neighbour across an edge that f loses is edited too. One across an edge f keeps (same
    // corners in the same slot; a vertex split relabels one corner) stays as it is: update()
    // refreshes the adjacency of f's neighbours anyway, and an edited face would cut the tree
    // there and re-lay out the smaller side for nothing.
    const int n = adj_[f][k];
    const bool kept_edge = corners[k] == c[k] && corners[(k + 1) % 3] == c[(k + 1) % 3];
    if (n >= 0 && !kept_edge && !is_dirty_[n]) {
      is_dirty_[n] = 1;
      dirty_.push_back(n);
    }
  }
  c = corners;
  for (int k = 0; k < 3; ++k) {
    half_edges_[half_edge_key(c[k], c[(k + 1) % 3])] = 3 * f + k;
    vertex_faces_[c[k]].push_back(f);
  }
  if (!is_dirty_[f]) {
    is_dirty_[f] = 1;
    dirty_.push_back(f);
  }
}

int Unfolding::add_face(std::array<int, 3> corners) {
  const int f = static_cast<int>(mesh_.faces.size());
  for (int v : corners)
    if (v < 0 || v >= static_cast<int>(mesh_.vertices.size()))
      throw TopologyException("a new face uses vertex " + std::to_string(v) +
                              ", which does not exist");
  mesh_.faces.push_back(corners);
  adj_.push_back({-1, -1, -1});
  adj_edge_.push_back({-1, -1, -1});
  links_.push_back(0);
  shape_.emplace_back();
  parent_.push_back(-2);  // not in the tree yet
  pos_.emplace_back();
  box_.emplace_back();
  overlaps_.emplace_back();
  overlapping_index_.push_back(-1);
  tin_.push_back(0);
  seen_.push_back(0);
  is_dirty_.push_back(1);
  dirty_.push_back(f);
  for (int k = 0; k < 3; ++k) {
    half_edges_[half_edge_key(corners[k], corners[(k + 1) % 3])] = 3 * f + k;
    vertex_faces_[corners[k]].push_back(f);
  }
  return f;
}

void Unfolding::attach(int f, int parent) {
  parent_.at(f) = parent;
  if (!is_dirty_[f]) {
    is_dirty_[f] = 1;
    dirty_.push_back(f);
  }
}

void Unfolding::insert_between(int f, int a, int b) {
  if (parent_.at(f) != -2) throw TopologyException(face_name(f) + " is already in the tree");
  if (parent_.at(a) == b) std::swap(a, b);
  if (parent_.at(b) != a)
    throw TopologyException(face_name(a) + " and " + face_name(b) + " are not linked");
  parent_[f] = a;
  parent_[b] = f;
  for (int x : {f, b})
    if (!is_dirty_[x]) {
      is_dirty_[x] = 1;
      dirty_.push_back(x);
    }
}

void Unfolding::set_adjacency(int f) {
  const auto& c = mesh_.faces[f];
  for (int k = 0; k < 3; ++k) {
    const auto own = half_edges_.find(half_edge_key(c[k], c[(k + 1) % 3]));
    if (own == half_edges_.end() || own->second != 3 * f + k)
      throw TopologyException("edge " + std::to_string(c[k]) + "-" +
                              std::to_string(c[(k + 1) % 3]) + " of " + face_name(f) +
                              " is used in the same direction by another face");
    const auto it = half_edges_.find(half_edge_key(c[(k + 1) % 3], c[k]));
    if (it == half_edges_.end()) {
      adj_[f][k] = -1;
      adj_edge_[f][k] = -1;
    } else {
      adj_[f][k] = it->second / 3;
      adj_edge_[f][k] = static_cast<std::int8_t>(it->second % 3);
    }
  }
}

std::size_t Unfolding::update() {
  if (dirty_.empty()) return pair_count_;
  const int nf = static_cast<int>(mesh_.faces.size());

  // Adjacency and shape of what changed, and of the faces now next to it.
  std::vector<int> around = dirty_;
  for (int f : dirty_) set_adjacency(f);
  for (int f : dirty_)
    for (int n : adj_[f])
      if (n >= 0 && !is_dirty_[n]) around.push_back(n);
  for (std::size_t i = dirty_.size(); i < around.size(); ++i) set_adjacency(around[i]);
  for (int f : dirty_) shape_[f] = checked_shape(mesh_, f);

  std::vector<int> moved;
  if (link_bits_ > 0 && 8 * dirty_.size() < static_cast<std::size_t>(nf) &&
      update_locally(around, moved)) {
    relaid_ += moved.size();
    for (int f : dirty_) is_dirty_[f] = 0;
    dirty_.clear();
    return pair_count_;
  }

  // Links from parents, and a check that they form one spanning tree.
  int root = -1;
  std::size_t link_count = 0;
  std::fill(links_.begin(), links_.end(), 0);
  for (int f = 0; f < nf; ++f) {
    const int p = parent_[f];
    if (p == -1) {
      if (root >= 0)
        throw TopologyException("the unfold tree has two roots: " + face_name(root) + " and " +
                                face_name(f));
      root = f;
      continue;
    }
    if (p < -1 || p >= nf) throw TopologyException(face_name(f) + " is not in the unfold tree");
    const int k = edge_to(f, p);
    if (k < 0)
      throw TopologyException(face_name(f) + " hangs from " + face_name(p) +
                              ", which shares no edge with it");
    if (!(links_[f] >> k & 1)) ++link_count;
    links_[f] |= 1 << k;
    links_[p] |= 1 << adj_edge_[f][k];
  }
  if (root < 0) throw TopologyException("the unfold tree has no root");

  // Parts of the tree without dirty faces; the largest keeps its layout.
  std::vector<int> part(nf, -1);
  std::vector<int> stack;
  int best = -1, parts = 0;
  std::size_t best_size = 0, reached = 0;
  for (int s = 0; s < nf; ++s) {
    if (part[s] >= 0 || is_dirty_[s]) continue;
    std::size_t size = 0;
    part[s] = parts;
    stack.push_back(s);
    while (!stack.empty()) {
      const int x = stack.back();
      stack.pop_back();
      ++size;
      for (int k = 0; k < 3; ++k)
        if (links_[x] >> k & 1) {
          const int n = adj_[x][k];
          if (part[n] < 0 && !is_dirty_[n]) {
            part[n] = parts;
            stack.push_back(n);
          }
        }
    }
    if (size > best_size) best_size = size, best = s;
    ++parts;
  }
  const int anchor = best >= 0 ? best : root;
  const int kept = best >= 0 ? part[best] : -1;
  reroot(anchor);

  // Re-lay-out everything outside the kept part, from the anchor down.
  std::vector<std::pair<int, int>> todo{{anchor, -1}};
  if (kept < 0) {
    pos_[anchor] = place_root(mesh_, anchor, shape_[anchor]);
    moved.push_back(anchor);
  }
  while (!todo.empty()) {
    const auto [x, from] = todo.back();
    todo.pop_back();
    if (++reached > static_cast<std::size_t>(nf)) break;  // links with a cycle
    for (int k = 0; k < 3; ++k) {
      const int n = adj_[x][k];
      if (!(links_[x] >> k & 1) || n == from) continue;
      if (kept < 0 || part[n] != kept) {
        pos_[n] = place_across(pos_[x], k, adj_edge_[x][k], shape_[n]);
        moved.push_back(n);
      }
      todo.push_back({n, x});
    }
  }
  if (reached != static_cast<std::size_t>(nf) || link_count != static_cast<std::size_t>(nf - 1))
    throw TopologyException("the unfold tree is not one spanning tree (it reaches " +
                            std::to_string(reached) + " of " + std::to_string(nf) + " faces)");

  link_bits_ = 2 * link_count;
  relaid_ += moved.size();
  test_moved(moved);
  for (int f : dirty_) is_dirty_[f] = 0;
  dirty_.clear();
  return pair_count_;
}

}  // namespace papernet
