#include "core/mesh/angle_defects.h"

#include <cmath>
#include <numbers>

#include "core/mesh/dual_graph.h"

namespace papernet {

std::vector<double> angle_sums(const Mesh& mesh) {
  std::vector<double> sum(mesh.vertices.size(), 0);
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = mesh.vertices[f[k]];
      const Vec3 a = mesh.vertices[f[(k + 1) % 3]] - p, b = mesh.vertices[f[(k + 2) % 3]] - p;
      sum[f[k]] += std::atan2(norm(cross(a, b)), dot(a, b));
    }
  return sum;
}

std::vector<double> angle_defects(const Mesh& mesh) {
  const std::vector<double> sum = angle_sums(mesh);
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& f : mesh.faces)
    for (const int v : f) used[v] = 1;
  const std::vector<char> boundary = boundary_vertices(mesh, build_dual_graph(mesh));
  std::vector<double> out(mesh.vertices.size(), 0);
  for (std::size_t v = 0; v < out.size(); ++v)
    if (used[v] && !boundary[v]) out[v] = 2 * std::numbers::pi - sum[v];
  return out;
}

}  // namespace papernet
