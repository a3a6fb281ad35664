#include "core/mesh/progressive_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <unordered_map>

#include "core/errors.h"

namespace papernet {
namespace {

void erase_value(std::vector<int>& list, int value) {
  const auto it = std::find(list.begin(), list.end(), value);
  if (it != list.end()) {
    *it = list.back();
    list.pop_back();
  }
}

bool contains(const std::array<int, 3>& face, int v) {
  return face[0] == v || face[1] == v || face[2] == v;
}

int third_corner(const std::array<int, 3>& face, int a, int b) {
  for (int c : face)
    if (c != a && c != b) return c;
  return -1;
}

int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// A face is degenerate for us when its height over its longest edge is below this fraction of
// that edge: such slivers make 2D layouts and overlap tests ill-conditioned.
constexpr double kMinShape = 1e-6;

// Most faces a collapse may leave around the kept vertex.
constexpr std::size_t kMaxValence = 24;

bool degenerate(Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 n = cross(b - a, c - a);
  const double l = std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)});
  const double n2 = dot(n, n);
  return !(n2 > kMinShape * kMinShape * l * l);
}

}  // namespace

ProgressiveMesh::ProgressiveMesh(Mesh mesh) : mesh_(std::move(mesh)) {
  const int nv = static_cast<int>(mesh_.vertices.size());
  const int nf = static_cast<int>(mesh_.faces.size());
  vertex_faces_.resize(nv);
  face_alive_.assign(nf, 1);
  face_count_ = static_cast<std::size_t>(nf);
  for (const Vec3& p : mesh_.vertices)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InvalidInputException("vertex with a non-finite coordinate");
  std::unordered_map<long long, int> directed;
  directed.reserve(static_cast<std::size_t>(nf) * 3);
  auto key = [nv](int a, int b) { return static_cast<long long>(a) * nv + b; };
  for (int f = 0; f < nf; ++f) {
    const auto& face = mesh_.faces[f];
    for (int k = 0; k < 3; ++k) {
      if (face[k] < 0 || face[k] >= nv)
        throw InvalidInputException("face " + std::to_string(f) +
                                    " has a vertex index out of range");
    }
    if (face[0] == face[1] || face[1] == face[2] || face[2] == face[0])
      throw InvalidInputException("face " + std::to_string(f) + " repeats a vertex");
    for (int k = 0; k < 3; ++k) {
      if (!directed.emplace(key(face[k], face[(k + 1) % 3]), f).second)
        throw InvalidInputException("edge (" + std::to_string(face[k]) + ", " +
                                    std::to_string(face[(k + 1) % 3]) +
                                    ") is non-manifold or inconsistently oriented");
      vertex_faces_[face[k]].push_back(f);
    }
  }
  // Every vertex must have one fan of faces: walk around it across shared edges.
  std::size_t edges = 0;
  std::vector<int> loop_parent(nv);
  std::iota(loop_parent.begin(), loop_parent.end(), 0);
  std::vector<int> comp_parent(nv);
  std::iota(comp_parent.begin(), comp_parent.end(), 0);
  for (int f = 0; f < nf; ++f) {
    const auto& face = mesh_.faces[f];
    for (int k = 0; k < 3; ++k) {
      const int a = face[k], b = face[(k + 1) % 3];
      comp_parent[find_root(comp_parent, a)] = find_root(comp_parent, b);
      const bool twin = directed.count(key(b, a)) != 0;
      if (!twin) {
        ++edges;
        loop_parent[find_root(loop_parent, a)] = find_root(loop_parent, b);
      } else if (a < b) {
        ++edges;
      }
    }
  }
  std::size_t components = 0, loops = 0;
  for (int v = 0; v < nv; ++v) {
    const auto& around = vertex_faces_[v];
    if (around.empty()) continue;
    ++vertex_count_;
    if (find_root(comp_parent, v) == v) ++components;
    // Rotate from the first face; count faces reached in both directions.
    std::size_t reached = 1;
    for (int dir = 0; dir < 2; ++dir) {
      int f = around[0];
      for (std::size_t step = 0; step < around.size(); ++step) {
        const auto& face = mesh_.faces[f];
        const int i = face[0] == v ? 0 : face[1] == v ? 1 : 2;
        // dir 0: across (v, next) into the face holding (next, v); dir 1: across (prev, v).
        const auto it = dir == 0 ? directed.find(key(face[(i + 1) % 3], v))
                                 : directed.find(key(v, face[(i + 2) % 3]));
        if (it == directed.end()) break;
        f = it->second;
        if (f == around[0]) {
          dir = 2;  // closed fan: everything reached going one way
          break;
        }
        ++reached;
      }
      if (dir == 2) break;
    }
    if (reached != around.size())
      throw InvalidInputException("vertex " + std::to_string(v) +
                                  " is non-manifold (its faces form several fans)");
  }
  // Boundary loops are the components of the boundary edges' graph.
  std::vector<char> on_boundary(nv, 0);
  for (const auto& face : mesh_.faces)
    for (int k = 0; k < 3; ++k)
      if (!directed.count(key(face[(k + 1) % 3], face[k])))
        on_boundary[face[k]] = on_boundary[face[(k + 1) % 3]] = 1;
  for (int v = 0; v < nv; ++v)
    if (on_boundary[v] && find_root(loop_parent, v) == v) ++loops;
  boundary_loops_ = static_cast<int>(loops);
  const long long chi = static_cast<long long>(vertex_count_) - static_cast<long long>(edges) + nf;
  genus_ = static_cast<int>(
      (2 * static_cast<long long>(components) - static_cast<long long>(loops) - chi) / 2);
}

bool ProgressiveMesh::is_boundary_edge(int a, int b) const {
  int count = 0;
  for (int f : vertex_faces_[a])
    if (contains(mesh_.faces[f], b)) ++count;
  return count == 1;
}

bool ProgressiveMesh::is_boundary_vertex(int v) const {
  // v's faces form one fan (a manifold, consistently oriented mesh). Each face contributes its
  // two other corners: in a closed fan every neighbour is the corner after v in one face and the
  // corner before v in another, so the XOR of all of them is 0; an open fan has two neighbours
  // (the fan's two ends, distinct) that appear once, so the XOR is theirs, never 0.
  int x = 0;
  for (int f : vertex_faces_[v]) {
    const auto& face = mesh_.faces[f];
    x ^= face[0] ^ face[1] ^ face[2] ^ v;
  }
  return x != 0;
}

int ProgressiveMesh::face_across(int f, int a, int b) const {
  for (int g : vertex_faces_[a])
    if (g != f && contains(mesh_.faces[g], b)) return g;
  return -1;
}

bool ProgressiveMesh::can_collapse(int vertex, int kept, Vec3 position) const {
  const int r = vertex, k = kept;
  if (r == k || r < 0 || k < 0 || r >= static_cast<int>(vertex_faces_.size()) ||
      k >= static_cast<int>(vertex_faces_.size()))
    return false;
  if (!vertex_alive(r) || !vertex_alive(k)) return false;
  if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
    return false;
  int gone[2] = {-1, -1}, opposite[2] = {-1, -1};
  int n_gone = 0;
  for (int f : vertex_faces_[r]) {
    if (!contains(mesh_.faces[f], k)) continue;
    if (n_gone == 2) return false;
    gone[n_gone] = f;
    opposite[n_gone] = third_corner(mesh_.faces[f], r, k);
    ++n_gone;
  }
  if (n_gone == 0 || face_count_ <= static_cast<std::size_t>(n_gone)) return false;
  // Valence cap: hubs make slivers and make every check around them slow.
  if (vertex_faces_[r].size() + vertex_faces_[k].size() - 2 * n_gone > kMaxValence) return false;
  if (n_gone == 2 && is_boundary_vertex(r) && is_boundary_vertex(k)) return false;
  // Link condition: the common neighbours of r and k are exactly the edge's opposite vertices.
  // Marks instead of two sorted rings (this runs for up to 12 candidates per queued vertex).
  thread_local std::vector<std::uint32_t> mark;
  thread_local std::uint32_t epoch = 0;
  if (mark.size() < mesh_.vertices.size()) mark.resize(mesh_.vertices.size(), 0);
  if (++epoch == 0) {
    std::fill(mark.begin(), mark.end(), 0);
    epoch = 1;
  }
  for (int f : vertex_faces_[r])
    for (int c : mesh_.faces[f])
      if (c != r) mark[c] = epoch;
  int common = 0;
  for (int f : vertex_faces_[k])
    for (int x : mesh_.faces[f]) {
      if (x == k || mark[x] != epoch) continue;
      mark[x] = 0;  // counted once
      if (x != opposite[0] && x != opposite[1]) return false;
      ++common;
    }
  if (common != n_gone) return false;
  // A face (r, a, b) must not become a copy of an existing (k, a, b) (a tetrahedron's
  // collapse); by the link condition a and b can only be the two opposite vertices.
  if (n_gone == 2) {
    const auto holds_ab = [&](int v) {
      for (int f : vertex_faces_[v])
        if (f != gone[0] && f != gone[1] && contains(mesh_.faces[f], opposite[0]) &&
            contains(mesh_.faces[f], opposite[1]))
          return true;
      return false;
    };
    if (holds_ab(r) && holds_ab(k)) return false;
  }
  // Geometry: no flipped normal, no degenerate face among the faces that change.
  for (int side = 0; side < 2; ++side) {
    const int v = side == 0 ? r : k;
    for (int f : vertex_faces_[v]) {
      if (f == gone[0] || f == gone[1]) continue;
      const auto& face = mesh_.faces[f];
      Vec3 p[3], q[3];
      for (int c = 0; c < 3; ++c) {
        p[c] = mesh_.vertices[face[c]];
        q[c] = face[c] == r || face[c] == k ? position : p[c];
      }
      if (degenerate(q[0], q[1], q[2])) return false;
      if (dot(cross(p[1] - p[0], p[2] - p[0]), cross(q[1] - q[0], q[2] - q[0])) <= 0) return false;
    }
  }
  return true;
}

void ProgressiveMesh::collapse(int vertex, int kept, Vec3 position) {
  if (!try_collapse(vertex, kept, position))
    throw TopologyException("illegal collapse of vertex " + std::to_string(vertex) + " into " +
                            std::to_string(kept));
}

bool ProgressiveMesh::try_collapse(int vertex, int kept, Vec3 position) {
  if (!can_collapse(vertex, kept, position)) return false;
  const int r = vertex, k = kept;
  VertexSplit s;
  s.vertex = r;
  s.vertex_position = mesh_.vertices[r];
  s.moved = k;
  s.moved_from = position;
  s.moved_to = mesh_.vertices[k];
  for (int f : vertex_faces_[r]) {
    const auto& face = mesh_.faces[f];
    if (contains(face, k)) {
      const int w = third_corner(face, r, k);
      s.new_faces.push_back({f, face, {face_across(f, r, w), face_across(f, k, w)}});
    } else {
      const int c = face[0] == r ? 0 : face[1] == r ? 1 : 2;
      s.relabelled.emplace_back(f, c);
      s.reshaped.push_back(f);
    }
  }
  for (int f : vertex_faces_[k])
    if (!contains(mesh_.faces[f], r)) s.reshaped.push_back(f);
  for (const SplitFace& gone : s.new_faces) {
    face_alive_[gone.face] = 0;
    for (int c : gone.corners) erase_value(vertex_faces_[c], gone.face);
  }
  for (const auto& [f, c] : s.relabelled) {
    mesh_.faces[f][c] = k;
    vertex_faces_[k].push_back(f);
  }
  vertex_faces_[r].clear();
  mesh_.vertices[k] = position;
  face_count_ -= s.new_faces.size();
  --vertex_count_;
  splits_.push_back(std::move(s));
  return true;
}

VertexSplit ProgressiveMesh::split() {
  VertexSplit s = std::move(splits_.back());
  splits_.pop_back();
  const int r = s.vertex, k = s.moved;
  mesh_.vertices[k] = s.moved_to;
  for (const auto& [f, c] : s.relabelled) {
    mesh_.faces[f][c] = r;
    erase_value(vertex_faces_[k], f);
    vertex_faces_[r].push_back(f);
  }
  for (const SplitFace& back : s.new_faces) {
    face_alive_[back.face] = 1;
    for (int c : back.corners) vertex_faces_[c].push_back(back.face);
  }
  face_count_ += s.new_faces.size();
  ++vertex_count_;
  return s;
}

Mesh ProgressiveMesh::compact(std::vector<int>* face_ids, std::vector<int>* vertex_ids) const {
  Mesh out;
  std::vector<int> index(mesh_.vertices.size(), -1);
  if (vertex_ids) vertex_ids->clear();
  if (face_ids) face_ids->clear();
  for (std::size_t v = 0; v < mesh_.vertices.size(); ++v) {
    if (vertex_faces_[v].empty()) continue;
    index[v] = static_cast<int>(out.vertices.size());
    out.vertices.push_back(mesh_.vertices[v]);
    if (vertex_ids) vertex_ids->push_back(static_cast<int>(v));
  }
  for (std::size_t f = 0; f < mesh_.faces.size(); ++f) {
    if (!face_alive_[f]) continue;
    const auto& face = mesh_.faces[f];
    out.faces.push_back({index[face[0]], index[face[1]], index[face[2]]});
    if (face_ids) face_ids->push_back(static_cast<int>(f));
  }
  return out;
}

}  // namespace papernet
