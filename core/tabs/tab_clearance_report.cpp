// Tab room report: blocked cut edges classified by where they sit in the cut graph.
#include "core/tabs/tab_clearance_report.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/mesh/angle_defects.h"
#include "core/mesh/dual_graph.h"
#include "core/tabs/internal/tab_clearance_params.h"
#include "core/unfold/folds.h"
#include "core/unfold/overlap.h"

namespace papernet {

namespace {

// leaf_room, given the mesh's angle defects.
std::vector<char> leaf_room(const Mesh& mesh, const TabClearanceOptions& options,
                            const std::vector<double>& defect) {
  const std::size_t nv = mesh.vertices.size();
  std::vector<char> out(nv, 0);
  if (!(options.min_height > 0)) {  // no minimum height: every edge has room
    for (std::size_t v = 0; v < nv; ++v) out[v] = defect[v] > 0;
    return out;
  }
  // Around each vertex v, its faces as (a, b) for face (v, a, b), counter-clockwise.
  std::vector<std::vector<std::pair<int, int>>> fan(nv);
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k) fan[f[k]].push_back({f[(k + 1) % 3], f[(k + 2) % 3]});
  const std::vector<TabShape> shapes = tab_shapes(options.angle_deg);
  const double tol = kTabRoomOverlapTolerance * bounding_box_diagonal(mesh);
  std::vector<Triangle2> flat;
  const auto hits_fan = [&](const Triangle2& t0, const Triangle2& t1, const Box2&) {
    return std::any_of(flat.begin(), flat.end(), [&](const Triangle2& c) {
      return triangles_overlap(t0, c, tol) || triangles_overlap(t1, c, tol);
    });
  };
  for (std::size_t v = 0; v < nv; ++v) {
    if (!(defect[v] > 0)) continue;  // also the boundary (defect 0 there)
    const Vec3 pv = mesh.vertices[v];
    for (const auto& [w, unused] : fan[v]) {
      // The fan opened at edge (v, w): faces (v, w, b1), (v, b1, b2), ..., (v, bn, w).
      flat.clear();
      double angle = 0;
      int a = w;
      Vec2 pa{norm(mesh.vertices[w] - pv), 0};
      while (flat.size() < fan[v].size()) {
        const auto next = std::find_if(fan[v].begin(), fan[v].end(),
                                       [&](const std::pair<int, int>& e) { return e.first == a; });
        if (next == fan[v].end()) break;
        const int b = next->second;
        const Vec3 da = mesh.vertices[a] - pv, db = mesh.vertices[b] - pv;
        angle += std::atan2(norm(cross(da, db)), dot(da, db));
        const double r = norm(db);
        const Vec2 pb{r * std::cos(angle), r * std::sin(angle)};
        flat.push_back({Vec2{0, 0}, pa, pb});
        pa = pb, a = b;
        if (a == w) break;
      }
      if (a != w || flat.empty()) continue;  // not a closed fan (not a manifold vertex)
      // The edge's two sides: (v, w) on the first face, (w, v) on the last.
      if (tab_fits(flat.front(), 0, shapes, options.min_height, hits_fan) ||
          tab_fits(flat.back(), 2, shapes, options.min_height, hits_fan)) {
        out[v] = 1;
        break;
      }
    }
  }
  return out;
}

}  // namespace

std::vector<char> leaf_room(const Mesh& mesh, const TabClearanceOptions& options) {
  return leaf_room(mesh, options, angle_defects(mesh));
}

TabRoomReport describe_tab_room(const Mesh& mesh, const Net& net,
                                const TabClearanceOptions& options, double flat_defect,
                                const std::vector<EdgeSide>* blocked) {
  TabRoomReport r;
  r.blocked_leaf_defects.assign(180, 0);
  r.leaf_defects.assign(180, 0);
  const std::size_t nv = mesh.vertices.size();
  const std::vector<double> defect = angle_defects(mesh);
  const std::vector<char> room = leaf_room(mesh, options, defect);
  r.leaf_room_vertices = static_cast<std::size_t>(std::count(room.begin(), room.end(), 1));
  const std::vector<NetEdge> edges = classify_edges(mesh, net);
  std::vector<int> degree(nv, 0);
  std::vector<char> boundary(nv, 0), used(nv, 0);
  for (const auto& f : mesh.faces)
    for (int v : f) used[v] = 1;
  for (const NetEdge& e : edges) {
    const int a = mesh.faces[e.a.face][e.a.k], b = mesh.faces[e.a.face][(e.a.k + 1) % 3];
    if (e.b.face < 0) {
      boundary[a] = boundary[b] = 1;
    } else if (e.kind == EdgeKind::Cut) {
      ++degree[a], ++degree[b], ++r.cut_edges;
    }
  }
  const auto bucket = [](double d) {
    return std::min<std::size_t>(179,
                                 static_cast<std::size_t>(std::abs(d) * 180 / std::numbers::pi));
  };
  const auto leaf = [&](int v) { return !boundary[v] && degree[v] == 1; };
  for (std::size_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    if (boundary[v]) {
      ++r.boundary_vertices;
    } else {
      ++r.interior_vertices;
      if (std::abs(defect[v]) >= flat_defect) ++r.sharp_vertices;
    }
    if (degree[v] >= 3) ++r.branch_vertices;
    if (leaf(static_cast<int>(v))) {
      ++r.leaves;
      ++r.leaf_defects[bucket(defect[v])];
      if (std::abs(defect[v]) < flat_defect) ++r.flat_leaves;
      if (!room[v]) ++r.leaves_without_room;
    }
  }
  // Cut edges by vertex, to walk hairs.
  std::vector<std::vector<int>> cut_at(nv);
  for (const NetEdge& e : edges)
    if (e.kind == EdgeKind::Cut && e.b.face >= 0)
      for (int j = 0; j < 2; ++j)
        cut_at[mesh.faces[e.a.face][(e.a.k + j) % 3]].push_back(
            j == 0 ? mesh.faces[e.a.face][(e.a.k + 1) % 3] : mesh.faces[e.a.face][e.a.k]);
  // Walks from vertex `at`, arrived from `from`, through two-cut interior vertices; true when
  // the walk ends at a leaf.
  const auto reaches_leaf = [&](int from, int at) {
    for (std::size_t steps = 0; steps < nv; ++steps) {
      if (leaf(at)) return true;
      if (boundary[at] || degree[at] != 2) return false;
      const int next = cut_at[at][0] == from ? cut_at[at][1] : cut_at[at][0];
      from = at, at = next;
    }
    return false;
  };
  for (const EdgeSide& s : blocked ? *blocked : edges_without_tab_room(mesh, net, options)) {
    ++r.blocked;
    const int a = mesh.faces[s.face][s.k], b = mesh.faces[s.face][(s.k + 1) % 3];
    if (leaf(a) || leaf(b)) {
      ++r.blocked_leaf;
      for (int v : {a, b})
        if (leaf(v)) {
          ++r.blocked_leaf_defects[bucket(defect[v])];
          if (!room[v]) ++r.leaves_without_room_blocked;
        }
    } else if (reaches_leaf(b, a) || reaches_leaf(a, b)) {
      ++r.blocked_hair;
    } else {
      ++r.blocked_other;
    }
  }
  return r;
}

}  // namespace papernet
