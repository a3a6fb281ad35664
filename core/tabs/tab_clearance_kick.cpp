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

#include "core/errors.h"
#include "core/tabs/internal/tab_clearance_kick.h"
#include "core/tabs/internal/tab_clearance_state.h"
#include "core/unfold/unfolding.h"

namespace papernet::tab_clearance_detail {

namespace {

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
          PassProgress& progress, TabClearanceResult& result) {
  const std::size_t budget = options.max_evaluations;
  if (result.blocked_after == 0 || budget == 0) return;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const bool timed = options.time_limit_seconds > 0;
  if (timed && seconds_left <= 0) return;
  const int nf = static_cast<int>(mesh.faces.size());
  std::size_t spent = 0;
  std::vector<char> was_blocked(3 * static_cast<std::size_t>(nf));  // in the current net
  double length = 0;  // mean edge length of the net, the scale of moved_faces' rounding
  for (const Triangle2& t : result.net.points)
    for (int k = 0; k < 3; ++k) length += norm(t[(k + 1) % 3] - t[k]);
  length /= 3.0 * std::max(1, nf);
  // A kick for blocked edge e of the current net `current`: kKicked when one was made (the net
  // changed), kStop when the budget or the time is spent.
  enum class Outcome { kNone, kKicked, kStop };
  const auto kick_edge = [&](const Clearance& current, const EdgeSide& e) {
    const int u = mesh.faces[e.face][e.k], v = mesh.faces[e.face][(e.k + 1) % 3];
    for (int w : {u, v})
      for (const auto& [lf, lk] : current.links_at(w))
        for (const auto& [cf, ck] : current.kick_glues(lf, lk, w)) {
          // A kick lays out the whole net again and recounts its blocked edges: it costs about
          // as much time as a candidate move per kKickFacesPerEvaluation faces.
          const std::size_t cost = 1 + mesh.faces.size() / kKickFacesPerEvaluation;
          if (spent + cost > budget || (timed && elapsed() >= seconds_left)) return Outcome::kStop;
          if (progress.cancelled()) throw CancelledException();
          progress.at(result.evaluations);
          spent += cost;
          result.evaluations += cost;
          Unfolding unfolding(mesh, current.swapped_tree(lf, lk, cf, ck));
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
          search_options.seconds_per_blocked_edge = 0;  // `seconds_left` has it taken off
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
                  for (int g : current.faces_at(z)) near[g] = 1;
          }
          search.focus_.assign(3 * static_cast<std::size_t>(nf), 0);
          for (int f = 0; f < nf; ++f)
            for (int k = 0; k < 3; ++k) {
              const int g = current.neighbour(f, k);
              search.focus_[3 * f + k] = !was_blocked[3 * f + k] || near[f] || (g >= 0 && near[g]);
            }
          search.run(progress, result.evaluations);
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
    return Outcome::kNone;
  };

  // Sweeps over the blocked edges of the current net in the order of their canonical half-edge,
  // each starting after the edge of the last kick; one without a kick ends the stage, as does the
  // budget.
  int resume = 0;
  for (Outcome outcome = Outcome::kKicked;
       outcome == Outcome::kKicked && result.blocked_after > 0;) {
    const Clearance current(mesh, result.net, options);
    std::vector<EdgeSide> blocked = current.blocked_edges();
    std::fill(was_blocked.begin(), was_blocked.end(), 0);
    for (const EdgeSide& e : blocked) was_blocked[3 * e.face + e.k] = 1;
    std::rotate(blocked.begin(),
                std::find_if(blocked.begin(), blocked.end(),
                             [&](const EdgeSide& e) { return 3 * e.face + e.k >= resume; }),
                blocked.end());
    outcome = Outcome::kNone;
    for (const EdgeSide& e : blocked) {
      outcome = kick_edge(current, e);
      if (outcome == Outcome::kNone) continue;
      resume = 3 * e.face + e.k + 1;
      break;
    }
  }
}

}  // namespace papernet::tab_clearance_detail
