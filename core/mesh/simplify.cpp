#include "core/mesh/simplify.h"

#include <algorithm>
#include <chrono>
#include <utility>
#include <vector>

#include "core/mesh/hausdorff.h"

namespace papernet {
namespace {

// Each step of the collapse for short edges removes this part of the faces left (then half of
// that, and so on, after a step that moved the surface too far).
constexpr std::size_t kShortEdgeStep = 6;

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
  const bool collapse = target.faces > 0 && target.faces < n;
  if (!collapse && !too_short(mesh)) return std::nullopt;
  ProgressiveMesh pm = decimate(mesh, {strategy, collapse ? target.faces : n}, progress);
  Mesh simple = pm.compact();
  const double diagonal = bounding_box_diagonal(mesh);
  std::size_t step = kShortEdgeStep;
  const auto start = std::chrono::steady_clock::now();
  const auto out_of_time = [&] {
    return target.seconds > 0 &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >=
               target.seconds;
  };
  while (too_short(simple) && !out_of_time()) {
    const std::size_t before = pm.face_count();
    ProgressiveMesh tried = pm;
    collapse_further(tried, strategy, before - std::max<std::size_t>(1, before / step), progress);
    if (tried.face_count() >= before) break;  // no legal collapse left
    Mesh next = tried.compact();
    if (approximation_distance(mesh, next) * diagonal > target.max_distance) {
      if (before / step <= 1) break;
      step *= 2;
      continue;
    }
    pm = std::move(tried);
    simple = std::move(next);
  }
  if (simple.faces.size() >= n) return std::nullopt;
  return simple;
}

}  // namespace papernet
