#include "core/mesh/tunnels.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <set>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "core/mesh/dual_graph.h"

namespace papernet {
namespace {

// The faces at each edge, the edges at each vertex, and the vertices where the surface is not a
// closed disc (on a boundary, or at an edge of more than two faces).
struct Topology {
  struct EdgeFaces {
    std::array<int, 2> face{-1, -1};
    int count = 0;
  };
  std::unordered_map<std::uint64_t, EdgeFaces> edges;
  std::vector<std::vector<std::pair<int, double>>> neighbours;  // (vertex, edge length)
  std::vector<char> open;

  explicit Topology(const Mesh& mesh)
      : neighbours(mesh.vertices.size()), open(mesh.vertices.size(), 0) {
    for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
      for (int i = 0; i < 3; ++i) {
        EdgeFaces& e = edges[edge_key(mesh.faces[f][i], mesh.faces[f][(i + 1) % 3])];
        if (e.count < 2) e.face[e.count] = f;
        ++e.count;
      }
    for (const auto& [key, e] : edges) {
      const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
      const double length = norm(mesh.vertices[a] - mesh.vertices[b]);
      neighbours[a].emplace_back(b, length);
      neighbours[b].emplace_back(a, length);
      if (e.count != 2) open[a] = open[b] = 1;
    }
  }
};

// True when cutting along the loop's edges (`cut`, sorted keys) leaves the faces on the two sides
// of its first edge apart: the loop separates the surface.
bool separates(const Mesh& mesh, const Topology& topology, const std::vector<int>& loop,
               const std::vector<std::uint64_t>& cut, std::vector<unsigned>& seen,
               unsigned& stamp) {
  const Topology::EdgeFaces& first = topology.edges.at(edge_key(loop[0], loop[1]));
  ++stamp;
  std::vector<int> stack{first.face[0]};
  seen[first.face[0]] = stamp;
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i) {
      const std::uint64_t key = edge_key(mesh.faces[f][i], mesh.faces[f][(i + 1) % 3]);
      if (std::binary_search(cut.begin(), cut.end(), key)) continue;
      const Topology::EdgeFaces& e = topology.edges.at(key);
      if (e.count != 2) continue;
      const int g = e.face[0] == f ? e.face[1] : e.face[0];
      if (g == first.face[1]) return false;
      if (seen[g] == stamp) continue;
      seen[g] = stamp;
      stack.push_back(g);
    }
  }
  return true;
}

}  // namespace

std::optional<std::vector<int>> shortest_tunnel_loop(const Mesh& mesh, double max_length) {
  const Topology topology(mesh);
  const auto nv = static_cast<int>(mesh.vertices.size());
  constexpr double kFar = std::numeric_limits<double>::infinity();
  std::vector<double> dist(nv, kFar);
  std::vector<int> parent(nv, -1), reached;
  std::vector<unsigned> on_path(nv, 0), seen(mesh.faces.size(), 0);
  unsigned path_stamp = 0, seen_stamp = 0;
  std::set<std::vector<std::uint64_t>> tried;
  std::optional<std::vector<int>> best_loop;
  double best = max_length;
  using Entry = std::pair<double, int>;
  for (int s = 0; s < nv; ++s) {
    if (topology.open[s] || topology.neighbours[s].empty()) continue;
    for (const int v : reached) dist[v] = kFar, parent[v] = -1;
    reached.clear();
    // Shortest paths from s over closed vertices, out to half the best loop so far: a loop
    // through a vertex farther than that from s is longer than the best.
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    dist[s] = 0;
    queue.emplace(0.0, s);
    while (!queue.empty()) {
      const auto [d, u] = queue.top();
      queue.pop();
      if (d > dist[u]) continue;
      reached.push_back(u);
      for (const auto& [w, length] : topology.neighbours[u]) {
        const double next = d + length;
        if (topology.open[w] || next > 0.5 * best || next >= dist[w]) continue;
        if (dist[w] == kFar && w != s) reached.push_back(w);  // reset with the others
        dist[w] = next;
        parent[w] = u;
        queue.emplace(next, w);
      }
    }
    std::sort(reached.begin(), reached.end());
    reached.erase(std::unique(reached.begin(), reached.end()), reached.end());
    // Each edge between two reached vertices that is not a tree edge closes a loop through s.
    for (const int a : reached) {
      for (const auto& [b, length] : topology.neighbours[a]) {
        if (b < a || dist[b] == kFar || parent[a] == b || parent[b] == a) continue;
        const double total = dist[a] + dist[b] + length;
        if (total >= best) continue;
        // The two paths must meet only at s, else the loop is not simple.
        ++path_stamp;
        for (int v = a; v != s; v = parent[v]) on_path[v] = path_stamp;
        bool simple = true;
        for (int v = b; v != s && simple; v = parent[v]) simple = on_path[v] != path_stamp;
        if (!simple) continue;
        std::vector<int> loop;
        for (int v = a; v != s; v = parent[v]) loop.push_back(v);
        loop.push_back(s);
        std::reverse(loop.begin(), loop.end());
        for (int v = b; v != s; v = parent[v]) loop.push_back(v);
        std::vector<std::uint64_t> cut;
        for (std::size_t i = 0; i < loop.size(); ++i)
          cut.push_back(edge_key(loop[i], loop[(i + 1) % loop.size()]));
        std::sort(cut.begin(), cut.end());
        if (!tried.insert(cut).second) continue;
        if (separates(mesh, topology, loop, cut, seen, seen_stamp)) continue;
        best = total;
        best_loop = std::move(loop);
      }
    }
  }
  return best_loop;
}

Mesh plug_tunnel(const Mesh& mesh, const std::vector<int>& loop) {
  const auto k = static_cast<int>(loop.size());
  Mesh out = mesh;
  std::vector<std::vector<int>> faces_at(mesh.vertices.size());
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
    for (const int v : mesh.faces[f]) faces_at[v].push_back(f);
  // The face with the half-edge from -> to, and its corner at `from`.
  const auto face_from = [&](int from, int to) -> std::pair<int, int> {
    for (const int f : faces_at[from])
      for (int i = 0; i < 3; ++i)
        if (mesh.faces[f][i] == from && mesh.faces[f][(i + 1) % 3] == to) return {f, i};
    return {-1, -1};
  };
  std::vector<int> copy(k);
  for (int i = 0; i < k; ++i) {
    copy[i] = static_cast<int>(out.vertices.size());
    out.vertices.push_back(mesh.vertices[loop[i]]);
  }
  // The faces left of the loop (with its half-edges in its direction) take the copies: around
  // each loop vertex, from the face with the half-edge to the next loop vertex, turning until the
  // face with the half-edge from the previous one.
  for (int i = 0; i < k; ++i) {
    const int v = loop[i], next = loop[(i + 1) % k], prev = loop[(i + k - 1) % k];
    auto [f, corner] = face_from(v, next);
    for (std::size_t turns = 0; f >= 0 && turns < faces_at[v].size(); ++turns) {
      out.faces[f][corner] = copy[i];
      const int third = mesh.faces[f][(corner + 2) % 3];
      if (third == prev) break;
      std::tie(f, corner) = face_from(v, third);
    }
  }
  const auto centroid = [&] {
    Vec3 c{0, 0, 0};
    for (const int v : loop) c = c + mesh.vertices[v];
    return (1.0 / k) * c;
  };
  if (k == 3) {
    out.faces.push_back({copy[0], copy[2], copy[1]});
    out.faces.push_back({loop[0], loop[1], loop[2]});
    return out;
  }
  const int left = static_cast<int>(out.vertices.size()), right = left + 1;
  out.vertices.push_back(centroid());
  out.vertices.push_back(centroid());
  for (int i = 0; i < k; ++i) {
    out.faces.push_back({left, copy[(i + 1) % k], copy[i]});
    out.faces.push_back({right, loop[i], loop[(i + 1) % k]});
  }
  return out;
}

}  // namespace papernet
