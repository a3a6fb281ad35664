// Mesh validation: every fault is counted and located, so a refusal can say what to fix.
#include "core/mesh/validate.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <unordered_map>

#include "core/mesh/internal/describe.h"
#include "core/union_find.h"

namespace papernet {
namespace {

using mesh_detail::plural;
using mesh_detail::position;

/// "vertices 3 (0, 1, 2), 7 (...), ..." for the first few of `items`.
std::string list_vertices(const Mesh& m, const std::vector<int>& items, std::size_t total) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i)
    s += (i ? ", " : "") + std::to_string(items[i]) + " " + position(m, items[i]);
  if (total > items.size()) s += ", ...";
  return s;
}

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}

struct EdgeUse {
  int faces[2] = {-1, -1};
  bool forward[2] = {false, false};  // traversed from the smaller to the larger vertex
  int count = 0;
};

void check_mesh(const Mesh& m, const ValidateOptions& opt, ValidationReport& r) {
  const std::size_t nv = m.vertices.size(), nf = m.faces.size();
  r.vertices = nv;
  r.faces = nf;
  if (nf == 0) {
    r.problems.push_back({"empty_mesh", "the mesh has no faces", true, {}});
    return;
  }
  auto add = [&](std::string code, std::string message, std::vector<int> where) {
    r.problems.push_back({std::move(code), std::move(message), true, std::move(where)});
  };
  // Only vertices that faces use count: the loader drops the rest.
  std::vector<int> bad_coords;
  std::size_t bad_count = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    const Vec3 p = m.vertices[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      if (++bad_count <= opt.max_listed) bad_coords.push_back(int(v));
  }
  if (bad_count)
    add("non_finite_coordinates",
        plural(bad_count, "vertex has", "vertices have") + " non-finite coordinates: vertices " +
            list_vertices(m, bad_coords, bad_count),
        bad_coords);

  std::vector<int> degenerate;
  std::size_t degenerate_count = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& t = m.faces[f];
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    const Vec3 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    const double longest = std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)});
    if (repeated || !(face_area(m, int(f)) > opt.degenerate_area * longest))
      if (++degenerate_count <= opt.max_listed) degenerate.push_back(int(f));
  }
  if (degenerate_count) {
    std::string where;
    for (int f : degenerate) where += (where.empty() ? "" : ", ") + std::to_string(f);
    if (degenerate_count > degenerate.size()) where += ", ...";
    add("degenerate_faces",
        plural(degenerate_count, "degenerate face", "degenerate faces") +
            " (zero area or a repeated vertex): faces " + where,
        degenerate);
  }

  // Edges: which faces use each, and in which direction.
  std::unordered_map<std::uint64_t, EdgeUse> edges;
  edges.reserve(nf * 2);
  // Faces with a repeated vertex are reported as degenerate and left out of the topology, so
  // that they do not also show up as non-manifold edges or pinched vertices.
  auto collapsed = [&](std::size_t f) {
    const auto& t = m.faces[f];
    return t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
  };
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3 && !collapsed(f); ++k) {
      const int a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
      EdgeUse& e = edges[edge_key(a, b)];
      if (e.count < 2) {
        e.faces[e.count] = int(f);
        e.forward[e.count] = a < b;
      }
      ++e.count;
    }
  r.edges = edges.size();
  std::vector<int> nm_edges, misoriented;
  std::size_t nm_count = 0, mis_count = 0;
  UnionFind boundary(nv), fans(3 * nf), components(nf);
  std::vector<char> on_nm_edge(nv, 0);
  auto corner = [&](int f, int v) {
    for (int k = 0; k < 3; ++k)
      if (m.faces[f][k] == v) return 3 * f + k;
    return 3 * f;
  };
  for (const auto& [key, e] : edges) {
    const int a = int(key >> 32), b = int(key & 0xffffffffu);
    if (e.count == 1) {
      ++r.boundary_edges;
      boundary.unite(a, b);
    } else if (e.count > 2) {
      on_nm_edge[a] = on_nm_edge[b] = 1;
      if (++nm_count <= opt.max_listed) nm_edges.insert(nm_edges.end(), {a, b});
    } else {
      if (e.forward[0] == e.forward[1] && ++mis_count <= opt.max_listed)
        misoriented.insert(misoriented.end(), {a, b});
      fans.unite(corner(e.faces[0], a), corner(e.faces[1], a));
      fans.unite(corner(e.faces[0], b), corner(e.faces[1], b));
    }
  }
  auto edge_list = [&](const std::vector<int>& ends, std::size_t total) {
    std::string s;
    for (std::size_t i = 0; i + 1 < ends.size(); i += 2)
      s += (i ? ", " : "") + std::to_string(ends[i]) + "-" + std::to_string(ends[i + 1]) + " " +
           position(m, ends[i]) + "-" + position(m, ends[i + 1]);
    if (total > ends.size() / 2) s += ", ...";
    return s;
  };
  if (nm_count)
    add("non_manifold_edges",
        plural(nm_count, "edge is", "edges are") + " shared by more than two faces: edges " +
            edge_list(nm_edges, nm_count),
        nm_edges);

  // A vertex is manifold when its faces form one fan joined across manifold edges. Vertices
  // on non-manifold edges are already reported with those edges.
  std::vector<int> fan_root(nv, -1);
  std::vector<char> pinched(nv, 0);
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3 && !collapsed(f); ++k) {
      const int v = m.faces[f][k];
      const int root = fans.find(int(3 * f + k));
      if (fan_root[v] < 0)
        fan_root[v] = root;
      else if (fan_root[v] != root)
        pinched[v] = 1;
    }
  std::vector<int> nm_vertices;
  std::size_t nmv_count = 0;
  for (std::size_t v = 0; v < nv; ++v)
    if (pinched[v] && !on_nm_edge[v] && ++nmv_count <= opt.max_listed)
      nm_vertices.push_back(int(v));
  if (nmv_count)
    add("non_manifold_vertices",
        plural(nmv_count, "vertex joins", "vertices join") +
            " faces that share no edge around it (a pinch): vertices " +
            list_vertices(m, nm_vertices, nmv_count),
        nm_vertices);
  if (mis_count)
    add("inconsistent_orientation",
        plural(mis_count, "edge has", "edges have") +
            " both faces running the same way (faces oriented inconsistently): edges " +
            edge_list(misoriented, mis_count),
        misoriented);

  // Components (faces joined through shared vertices), and per component V - E + F and b.
  std::vector<int> vertex_face(nv, -1);
  for (std::size_t f = 0; f < nf; ++f)
    for (int v : m.faces[f]) {
      if (vertex_face[v] >= 0) components.unite(int(f), vertex_face[v]);
      vertex_face[v] = int(f);
    }
  std::unordered_map<int, int> comp_index;
  std::vector<long> chi;
  std::vector<std::size_t> loops;
  auto comp_of_face = [&](int f) {
    const auto [it, fresh] = comp_index.try_emplace(components.find(f), int(chi.size()));
    if (fresh) {
      chi.push_back(0);
      loops.push_back(0);
    }
    return it->second;
  };
  // Faces with a repeated vertex and vertices only they use stay out of V - E + F, as out of E.
  std::vector<char> in_surface(nv, 0);
  for (std::size_t f = 0; f < nf; ++f) {
    const int c = comp_of_face(int(f));
    if (collapsed(f)) continue;
    ++chi[c];
    for (int v : m.faces[f]) in_surface[v] = 1;
  }
  for (std::size_t v = 0; v < nv; ++v)
    if (in_surface[v]) ++chi[comp_of_face(vertex_face[v])];
  std::vector<char> loop_seen(nv, 0);
  for (const auto& [key, e] : edges) {
    const int c = comp_of_face(e.faces[0]);
    --chi[c];
    if (e.count == 1) {
      const int root = boundary.find(int(key >> 32));
      if (!loop_seen[root]) {
        loop_seen[root] = 1;
        ++loops[c];
      }
    }
  }
  r.components = chi.size();
  r.genus = 0;
  r.boundary_loops = 0;
  for (std::size_t c = 0; c < chi.size(); ++c) {
    r.boundary_loops += loops[c];
    r.genus += (2 - chi[c] - long(loops[c])) / 2;
  }
  if (r.components > 1)
    add("several_components",
        "the mesh has " + std::to_string(r.components) +
            " separate components; a net is one piece (an option keeps the largest)",
        {});
}

Mesh largest_component(const Mesh& m) {
  UnionFind uf(m.faces.size());
  std::vector<int> vertex_face(m.vertices.size(), -1);
  for (std::size_t f = 0; f < m.faces.size(); ++f)
    for (int v : m.faces[f]) {
      if (vertex_face[v] >= 0) uf.unite(int(f), vertex_face[v]);
      vertex_face[v] = int(f);
    }
  std::unordered_map<int, std::size_t> size;
  for (std::size_t f = 0; f < m.faces.size(); ++f) ++size[uf.find(int(f))];
  int best = -1;
  std::size_t best_size = 0;
  for (std::size_t f = 0; f < m.faces.size(); ++f) {  // first in face order wins ties
    const int root = uf.find(int(f));
    if (size[root] > best_size) best = root, best_size = size[root];
  }
  std::vector<int> faces;
  for (std::size_t f = 0; f < m.faces.size(); ++f)
    if (uf.find(int(f)) == best) faces.push_back(int(f));
  return mesh_of_faces(m, faces);
}

}  // namespace

bool ValidationReport::unfoldable() const {
  return std::none_of(problems.begin(), problems.end(),
                      [](const MeshProblem& p) { return p.blocking; });
}

std::string ValidationReport::reason() const {
  for (const MeshProblem& p : problems)
    if (p.blocking) return p.message;
  return "";
}

ValidationReport validate(const Mesh& mesh, const ValidateOptions& options) {
  ValidationReport report;
  check_mesh(mesh, options, report);
  if (!options.keep_largest_component || report.components <= 1) return report;
  const std::size_t total_components = report.components, total_faces = report.faces;
  ValidationReport kept;
  kept.largest_component = largest_component(mesh);
  check_mesh(kept.largest_component, options, kept);
  kept.problems.insert(
      kept.problems.begin(),
      {"kept_largest_component",
       "kept the largest of " + std::to_string(total_components) + " components (" +
           std::to_string(kept.faces) + " of " + std::to_string(total_faces) + " faces)",
       false,
       {}});
  return kept;
}

ValidationReport validate(const LoadedMesh& loaded, const ValidateOptions& options) {
  ValidationReport report = validate(loaded.mesh, options);
  if (loaded.mesh.faces.empty() && loaded.raw_vertices > 0)
    report.problems.front().message = "the mesh has no faces: the file holds " +
                                      std::to_string(loaded.raw_vertices) +
                                      " vertices but no triangles (a point cloud or lines)";
  if (loaded.triangulated)
    report.problems.insert(report.problems.begin(),
                           {"triangulated",
                            "the file has polygons or strips; they were split into triangles",
                            false,
                            {}});
  return report;
}

}  // namespace papernet
