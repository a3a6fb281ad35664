// Kicks, one way of the tab clearance pass's second round (clear_tab_room): when the tabu search
// (Clearance::run) has stalled, a swap that opens a blocked edge is made even though it overlaps,
// the overlaps are removed by the unfolder's local repair (Unfolding::repair_locally, which knows
// nothing of tabs), and a short tabu search starts from the repaired net. Where the search alone
// stalls because every opening swap overlaps (80-97 % of them on dense meshes), this gets past.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <vector>

#include "core/dual_graph.h"
#include "core/errors.h"
#include "core/tab_clearance_report.h"
#include "core/tab_clearance_state.h"
#include "core/unfolding.h"

namespace papernet::tab_clearance_detail {

namespace {

// The unfold tree `parent` with the link between faces a and b cut and faces c and d (sharing
// an edge, on the two sides of that link) linked instead: the side that was cut off is re-rooted
// at whichever of c and d lies in it.
std::vector<int> swapped(std::vector<int> parent, int a, int b, int c, int d,
                         const std::vector<char>& in_cut_side) {
  const int top = parent[a] == b ? a : b;
  if (!in_cut_side[c]) std::swap(c, d);
  parent[top] = -1;
  for (int prev = d, at = c; at >= 0;) {
    const int next = parent[at];
    parent[at] = prev;
    prev = at;
    at = next;
  }
  return parent;
}

// Faces of net `after` that did not keep their place relative to the largest part of net
// `before` (the nets of the same mesh, each anywhere in the plane): each face's rigid motion from
// `before` to `after`, rounded, and every face whose motion is not the most common one.
std::vector<char> moved_faces(const Net& before, const Net& after, double length) {
  using Key = std::array<long long, 3>;
  const std::size_t n = before.points.size();
  std::vector<Key> keys(n);
  std::map<Key, std::size_t> count;
  for (std::size_t f = 0; f < n; ++f) {
    const Triangle2& p = before.points[f];
    const Triangle2& q = after.points[f];
    const Vec2 d0 = p[1] - p[0], d1 = q[1] - q[0];
    const double angle = std::atan2(cross(d0, d1), dot(d0, d1));
    const double c = std::cos(angle), s = std::sin(angle);
    const Vec2 t{q[0].x - (c * p[0].x - s * p[0].y), q[0].y - (s * p[0].x + c * p[0].y)};
    const double step = 1e-6 * length;
    keys[f] = {std::llround(angle * 1e6), std::llround(t.x / step), std::llround(t.y / step)};
    ++count[keys[f]];
  }
  Key most{};
  std::size_t best = 0;
  for (const auto& [key, c] : count)
    if (c > best) best = c, most = key;
  std::vector<char> moved(n);
  for (std::size_t f = 0; f < n; ++f) moved[f] = keys[f] != most;
  return moved;
}

}  // namespace

void kick(const Mesh& mesh, const TabClearanceOptions& options, double seconds_left,
          Progress& progress, TabClearanceResult& result) {
  const std::size_t budget = options.max_evaluations;
  if (result.blocked_after == 0 || budget == 0) return;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const bool timed = options.time_limit_seconds > 0;
  if (timed && seconds_left <= 0) return;
  const int nf = static_cast<int>(mesh.faces.size());
  const DualGraph graph = build_dual_graph(mesh);
  const std::vector<char> boundary = boundary_vertices(mesh, graph);
  const std::vector<double> defect = angle_defects(mesh);
  std::vector<std::vector<int>> vertex_faces(mesh.vertices.size());
  for (int f = 0; f < nf; ++f)
    for (int v : mesh.faces[f]) vertex_faces[v].push_back(f);
  const auto& adj = graph.neighbour;

  std::size_t spent = 0;
  std::vector<int> degree(mesh.vertices.size());
  std::vector<std::vector<int>> children(nf);
  std::vector<char> side(nf);
  std::vector<int> stack;
  std::vector<char> was_blocked(3 * static_cast<std::size_t>(nf));  // in the current net
  double length = 0;  // mean edge length of the net, the scale of moved_faces' rounding
  for (const Triangle2& t : result.net.points)
    for (int k = 0; k < 3; ++k) length += norm(t[(k + 1) % 3] - t[k]);
  length /= 3.0 * std::max(1, nf);
  // A kick for blocked edge e of the current net: true when one was made (the net changed).
  enum class Outcome { kNone, kKicked, kStop };
  const auto kick_edge = [&](const EdgeSide& e) {
    const std::vector<int>& parent = result.net.parent;
    const auto linked = [&](int f, int k) {
      const int g = adj[f][k];
      return g >= 0 && (parent[f] == g || parent[g] == f);
    };
    const int u = mesh.faces[e.face][e.k], v = mesh.faces[e.face][(e.k + 1) % 3];
    for (int w : {u, v})
      for (int x : vertex_faces[w])
        for (int j = 0; j < 3; ++j) {
          const int y = adj[x][j];
          const int a = mesh.faces[x][j], b = mesh.faces[x][(j + 1) % 3];
          if (y < x || !linked(x, j) || (a != w && b != w)) continue;
          // The side of the tree the link cuts off.
          std::fill(side.begin(), side.end(), 0);
          stack.assign(1, parent[x] == y ? x : y);
          while (!stack.empty()) {
            const int z = stack.back();
            stack.pop_back();
            side[z] = 1;
            stack.insert(stack.end(), children[z].begin(), children[z].end());
          }
          // Cut edges across the two sides whose gluing leaves no new flat leaf of the cut tree
          // (the link's own edge becomes a cut), nearest to w first.
          struct Glue {
            double distance;
            int f, k;
          };
          std::vector<Glue> glues;
          const auto new_flat_leaf = [&](int z) {
            const int left = degree[z] - 1 + (z == a || z == b ? 1 : 0);
            return !boundary[z] && (left == 0 || (left == 1 && std::abs(defect[z]) < kSharpDefect));
          };
          for (int f = 0; f < nf; ++f)
            for (int k = 0; k < 3; ++k) {
              const int g = adj[f][k];
              if (g < f || linked(f, k) || side[f] == side[g]) continue;
              const int p = mesh.faces[f][k], q = mesh.faces[f][(k + 1) % 3];
              if (new_flat_leaf(p) || new_flat_leaf(q)) continue;
              const Vec3 m = 0.5 * (mesh.vertices[p] + mesh.vertices[q]) - mesh.vertices[w];
              glues.push_back({dot(m, m), f, k});
            }
          std::stable_sort(glues.begin(), glues.end(),
                           [](const Glue& l, const Glue& r) { return l.distance < r.distance; });
          if (glues.size() > kKickGlues) glues.resize(kKickGlues);
          for (const Glue& glue : glues) {
            // A kick lays out the whole net again and recounts its blocked edges: it costs about
            // as much time as a candidate move per kKickFacesPerEvaluation faces.
            const std::size_t cost = 1 + mesh.faces.size() / kKickFacesPerEvaluation;
            if (spent + cost > budget || (timed && elapsed() >= seconds_left))
              return Outcome::kStop;
            if (progress.cancelled()) throw CancelledException();
            spent += cost;
            result.evaluations += cost;
            Unfolding unfolding(mesh, swapped(parent, x, y, glue.f, adj[glue.f][glue.k], side));
            LocalRepairStats repair;
            if (unfolding.overlap_count() > 0) {
              LocalRepairOptions repair_options;
              repair_options.max_tests = kKickRepairTests;
              unfolding.repair_locally(repair_options, &repair);
              if (unfolding.overlap_count() > 0) continue;
            }
            TabClearanceOptions search_options = options;
            search_options.max_evaluations = std::min(
                std::max<std::size_t>(1, budget / kKickSearches), budget - std::min(budget, spent));
            if (timed) search_options.time_limit_seconds = std::max(1e-3, seconds_left - elapsed());
            Clearance search(mesh, unfolding.net(), search_options);
            if (search.blocked_count() > result.blocked_after + kKickSlack) continue;
            // The search looks where the kick and the repair changed the net: edges at faces
            // that moved or within two rings of them, and edges that had room before.
            std::vector<char> near = moved_faces(result.net, search.net(), length);
            for (int ring = 0; ring < 2; ++ring) {
              const std::vector<char> inner = near;
              for (int f = 0; f < nf; ++f)
                if (inner[f])
                  for (int z : mesh.faces[f])
                    for (int g : vertex_faces[z]) near[g] = 1;
            }
            search.focus_.assign(3 * static_cast<std::size_t>(nf), 0);
            for (int f = 0; f < nf; ++f)
              for (int k = 0; k < 3; ++k)
                search.focus_[3 * f + k] =
                    !was_blocked[3 * f + k] || near[f] || (adj[f][k] >= 0 && near[adj[f][k]]);
            search.run(progress);
            spent += search.evaluations_;
            result.evaluations += search.evaluations_;
            if (search.blocked_count() >= result.blocked_after) continue;
            result.net = search.net();
            result.blocked_after = search.blocked_count();
            result.moves += 1 + repair.moves + search.moves_;
            result.compound_moves += search.compound_moves_;
            ++result.kicks;
            return Outcome::kKicked;
          }
        }
    return Outcome::kNone;
  };

  // Sweeps over the blocked edges of the current net in the order of their canonical half-edge,
  // each starting after the edge of the last kick; one without a kick ends the stage, as does the
  // budget.
  int resume = 0;
  for (Outcome outcome = Outcome::kKicked;
       outcome == Outcome::kKicked && result.blocked_after > 0;) {
    const std::vector<int>& parent = result.net.parent;
    std::fill(degree.begin(), degree.end(), 0);
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const int g = adj[f][k];
        if (f < g && parent[f] != g && parent[g] != f)
          ++degree[mesh.faces[f][k]], ++degree[mesh.faces[f][(k + 1) % 3]];
      }
    for (auto& c : children) c.clear();
    for (int f = 0; f < nf; ++f)
      if (parent[f] >= 0) children[parent[f]].push_back(f);
    std::vector<EdgeSide> blocked = edges_without_tab_room(mesh, result.net, options);
    std::fill(was_blocked.begin(), was_blocked.end(), 0);
    for (const EdgeSide& e : blocked) was_blocked[3 * e.face + e.k] = 1;
    std::rotate(blocked.begin(),
                std::find_if(blocked.begin(), blocked.end(),
                             [&](const EdgeSide& e) { return 3 * e.face + e.k >= resume; }),
                blocked.end());
    outcome = Outcome::kNone;
    for (const EdgeSide& e : blocked) {
      outcome = kick_edge(e);
      if (outcome == Outcome::kNone) continue;
      resume = 3 * e.face + e.k + 1;
      break;
    }
  }
}

}  // namespace papernet::tab_clearance_detail
