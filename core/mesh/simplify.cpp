#include "core/mesh/simplify.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/mesh/angle_defects.h"
#include "core/mesh/hausdorff.h"
#include "core/mesh/thin_faces.h"
#include "core/mesh/thin_plates.h"
#include "core/mesh/tunnels.h"

namespace papernet {
namespace {

// Each step of the collapse for short edges removes this part of the faces left (then half of
// that, and so on, after a step that moved the surface too far).
constexpr std::size_t kShortEdgeStep = 6;

// Short edges in a row that found no collapse alone (each point measured) after which the
// collapse of short edges one by one gives up: where the surface has no room left to move,
// trying all 688 short edges of a CAD part took 2.4 s.
constexpr std::size_t kMostFailedShortEdges = 16;

// The part of the distance allowed that one flip for thin faces may move the surface.
constexpr double kThinFaceMove = 0.25;

// True when the faces around a vertex of `m`'s border turn through more than a full turn: laid
// flat they overlap each other, and the surface is no single layer of card. The side of the
// tray bottom of bench/400, its short edges collapsed, had such a vertex of 461 degrees along
// its rim (TU searched it for 48 s and printed 7 pieces).
bool folds_over_its_border(const Mesh& m) {
  std::set<std::pair<int, int>> sides;
  for (const auto& t : m.faces)
    for (int i = 0; i < 3; ++i) sides.emplace(t[i], t[(i + 1) % 3]);
  std::vector<char> border(m.vertices.size(), 0);
  for (const auto& [a, b] : sides)
    if (!sides.count({b, a})) border[a] = border[b] = 1;
  const std::vector<double> turn = angle_sums(m);
  for (std::size_t v = 0; v < turn.size(); ++v)
    if (border[v] && turn[v] > 2 * std::numbers::pi + 1e-6) return true;
  return false;
}

}  // namespace

std::size_t count_short_edges(const Mesh& mesh, double length) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(mesh.faces.size() * 3);
  for (const auto& t : mesh.faces)
    for (int i = 0; i < 3; ++i) {
      const int a = t[i], b = t[(i + 1) % 3];
      if (norm(mesh.vertices[a] - mesh.vertices[b]) < length)
        edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  return static_cast<std::size_t>(std::unique(edges.begin(), edges.end()) - edges.begin());
}

std::optional<Mesh> simplify_mesh(const Mesh& mesh, CollapseStrategy strategy,
                                  const SimplifyTarget& target, Progress& progress) {
  const std::size_t n = mesh.faces.size();
  const auto too_short = [&](const Mesh& m) {
    return target.short_edge > 0 && double(count_short_edges(m, target.short_edge)) >
                                        target.short_edges_allowed * double(m.faces.size());
  };
  const double diagonal = bounding_box_diagonal(mesh);
  // The distance allowed, relative to the diagonal (as approximation_within measures).
  const double allowed =
      diagonal > 0 ? target.max_distance / diagonal : std::numeric_limits<double>::infinity();
  // The distance of each candidate to the input, measured against the input's face tree built
  // once, when first needed.
  std::optional<ApproximationMeasure> measured_from;
  const auto measure = [&]() -> const ApproximationMeasure& {
    if (!measured_from) measured_from.emplace(mesh);
    return *measured_from;
  };
  // A thin plate, its walls too narrow to fold, label or glue, is printed as one layer of card:
  // one of its sides (plate_side), when that is within the distance allowed.
  const auto one_side = [&](const Mesh& m) -> std::optional<Mesh> {
    if (!target.thin_plates) return std::nullopt;
    std::optional<Mesh> side = plate_side(m);
    if (side && (folds_over_its_border(*side) || !measure().within(*side, allowed))) side.reset();
    return side;
  };
  // The plate's side first (the collapse would keep its walls: no collapse may join its two
  // sides), then once more at the end (a part the collapse left a plate).
  const std::optional<Mesh> side = one_side(mesh);
  const Mesh& from = side ? *side : mesh;
  const bool collapse = target.faces > 0 && target.faces < from.faces.size();
  if (!collapse && !too_short(from)) {
    // Nothing to collapse, but thin faces may be left (a sliver across a T-junction of a CAD
    // export, all its edges long): their edges are flipped as at the end below.
    Mesh m = from;
    if (target.thin_face > 0 &&
        thicken_thin_faces(m, target.thin_face, kThinFaceMove * target.max_distance) > 0 &&
        measure().within(m, allowed)) {
      try {
        [[maybe_unused]] const ProgressiveMesh manifold(m);  // and oriented, as `take` asks
        return m;
      } catch (const InvalidInputException&) {
      }
    }
    return side;
  }
  ProgressiveMesh pm =
      decimate(from, {strategy, collapse ? target.faces : from.faces.size()}, progress);
  Mesh simple = pm.compact();
  std::size_t step = kShortEdgeStep;
  const auto start = std::chrono::steady_clock::now();
  const auto out_of_time = [&] {
    return target.seconds > 0 &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >=
               target.seconds;
  };
  // Plugs the tunnels of `m` whose loop around is at most target.max_tunnel_loop, one at a time
  // while the time lasts, and returns how many.
  const auto plug_small_tunnels = [&](Mesh& m) {
    std::size_t plugs = 0;
    while (target.max_tunnel_loop > 0 && !out_of_time())
      if (const std::optional<std::vector<int>> loop =
              shortest_tunnel_loop(m, target.max_tunnel_loop)) {
        m = plug_tunnel(m, *loop);
        ++plugs;
      } else {
        break;
      }
    return plugs;
  };
  // No collapse may close a tunnel, so a part with many small ones (holes through a plate)
  // collapsed to fewer faces than their walls need is crushed instead: trimesh ADIS16480 (genus
  // 24) at 100 mm kept 278 faces 17 % of its diagonal from the model, its box a heap. Where the
  // collapse to the faces asked moves the surface farther than allowed, the tunnels too small to
  // build are plugged on the most collapsed mesh still within it (undone in batches that double:
  // plugging the input itself took minutes on a scan of 76,840 faces), that is collapsed to the
  // faces asked, and kept when it moves the surface less.
  if (collapse && target.max_tunnel_loop > 0 && !measure().within(simple, allowed)) {
    ProgressiveMesh back = pm;
    for (std::size_t batch = 16; back.splits_left() > 0 && !out_of_time(); batch *= 2) {
      for (std::size_t i = 0; i < batch && back.splits_left() > 0; ++i) back.split();
      if (measure().within(back.compact(), allowed)) break;
    }
    Mesh m = back.compact();
    if (plug_small_tunnels(m) > 0) {
      try {
        ProgressiveMesh tried = decimate(m, {strategy, target.faces}, progress);
        Mesh next = tried.compact();
        if (measure().distance(next) < measure().distance(simple)) {
          pm = std::move(tried);
          simple = std::move(next);
        }
      } catch (const InvalidInputException&) {
        // not manifold and oriented after all: the collapse keeps what it has
      }
    }
  }
  // Takes `m` for the mesh collapsed so far when it is no farther than the distance allowed.
  const auto take = [&](Mesh& m) {
    if (!measure().within(m, allowed)) return false;
    try {
      pm = ProgressiveMesh(m);
    } catch (const InvalidInputException&) {
      return false;  // not manifold and oriented after all: the collapse keeps what it has
    }
    simple = std::move(m);
    step = kShortEdgeStep;
    return true;
  };
  // Flips edges of the thin faces of the mesh collapsed so far, and takes the result.
  const auto thickened = [&] {
    Mesh m = simple;
    return target.thin_face > 0 &&
           thicken_thin_faces(m, target.thin_face, kThinFaceMove * target.max_distance) > 0 &&
           take(m);
  };
  // Collapses the short edges themselves, shortest first, each into its middle or one of its
  // ends, and takes the result. The steps collapse in the strategy's order, whose cheapest
  // collapse may move the surface farther than a short edge's would: trimesh ADIS16480 stopped
  // at 282 faces with 39 edges of 1.7 to 3 mm, at slivers whose labels printed under 1.5 mm.
  // No collapse may leave a face lower than the lower of a thin face and the lowest face around
  // its edge: it would make a sliver. The distance is measured once for a batch of collapses;
  // a batch that moves the surface too far is undone and tried again half as large, and one
  // collapse alone tries each of the three points.
  const auto collapse_short_edges = [&] {
    ProgressiveMesh p(simple);  // simple's ids
    std::vector<std::pair<double, std::pair<int, int>>> edges;
    for (const auto& t : simple.faces)
      for (int i = 0; i < 3; ++i) {
        const int a = t[i], b = t[(i + 1) % 3];
        const double length = norm(simple.vertices[a] - simple.vertices[b]);
        if (a < b && length < target.short_edge) edges.push_back({length, {a, b}});
      }
    std::sort(edges.begin(), edges.end());
    // Collapses edge `e` at the first of its points that is legal and makes no sliver (and,
    // when `measured`, keeps the surface within the distance allowed); false when none does.
    const auto collapse_edge = [&](std::pair<int, int> e, bool measured) {
      const auto [a, b] = e;
      if (!p.vertex_alive(a) || !p.vertex_alive(b)) return false;
      const Vec3 at_a = p.mesh().vertices[a], at_b = p.mesh().vertices[b];
      if (!(norm(at_a - at_b) < target.short_edge)) return false;  // made longer since
      double lowest = target.thin_face;
      for (const int v : {a, b})
        for (const int f : p.vertex_faces(v)) lowest = std::min(lowest, face_height(p.mesh(), f));
      for (const auto& [gone, kept, at] : {std::tuple{b, a, 0.5 * (at_a + at_b)},
                                           std::tuple{b, a, at_a}, std::tuple{a, b, at_b}}) {
        if (!p.try_collapse(gone, kept, at)) continue;  // not an edge now, or not legal
        double low = std::numeric_limits<double>::infinity();
        for (const int f : p.vertex_faces(kept)) low = std::min(low, face_height(p.mesh(), f));
        if (low >= lowest && (!measured || measure().within(p.compact(), allowed))) return true;
        p.split();
      }
      return false;
    };
    std::size_t next = 0, batch = edges.size(), collapsed = 0, failed = 0;
    while (next < edges.size() && failed < kMostFailedShortEdges && !out_of_time()) {
      const bool one = batch == 1;
      std::size_t made = 0, end = next;
      while (end < edges.size() && made < batch && failed < kMostFailedShortEdges) {
        made += collapse_edge(edges[end++].second, one);
        if (one) failed = made ? 0 : failed + 1;
      }
      if (made == 0) break;
      if (one || measure().within(p.compact(), allowed)) {
        collapsed += made;
        next = end;
        batch = std::min(edges.size(), 2 * batch);
        continue;
      }
      for (; made > 0; --made) p.split();
      batch = std::max<std::size_t>(1, batch / 2);
    }
    if (collapsed == 0) return false;
    Mesh m = p.compact();
    return take(m);
  };
  // When no collapse is left that keeps the surface close enough, the small tunnels (a hole
  // through a plate, a gap under a handle) are plugged, else edges of thin faces are flipped,
  // else the short edges are collapsed one by one, and the collapse goes on from there; again
  // only after it has collapsed further (plugs add faces, and flips stop where no flip thickens
  // a face).
  bool reshaped = false;
  std::size_t stuck_at = std::numeric_limits<std::size_t>::max();
  const auto unstuck = [&] {
    if (pm.face_count() < stuck_at) {
      stuck_at = pm.face_count();
      Mesh m = simple;
      if ((plug_small_tunnels(m) > 0 && take(m)) || thickened()) return reshaped = true;
    }
    // Each such round leaves fewer faces, so this ends too.
    if (collapse_short_edges()) return reshaped = true;
    return false;
  };
  while (too_short(simple) && !out_of_time()) {
    const std::size_t before = pm.face_count();
    ProgressiveMesh tried = pm;
    collapse_further(tried, strategy, before - std::max<std::size_t>(1, before / step), progress);
    if (tried.face_count() >= before) {  // no legal collapse left
      if (unstuck()) continue;
      break;
    }
    Mesh next = tried.compact();
    if (!measure().within(next, allowed)) {
      if (before / step <= 1) {
        if (unstuck()) continue;
        break;
      }
      step *= 2;
      continue;
    }
    pm = std::move(tried);
    simple = std::move(next);
  }
  // Thin faces left where the short edges are few enough: their edges are flipped as well.
  if (!out_of_time() && thickened()) reshaped = true;
  if (!out_of_time())
    if (std::optional<Mesh> last = one_side(simple); last && take(*last)) reshaped = true;
  if (simple.faces.size() >= n && !reshaped && !side) return std::nullopt;
  return simple;
}

}  // namespace papernet
