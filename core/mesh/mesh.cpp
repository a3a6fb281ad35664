#include "core/mesh/mesh.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace papernet {

Vec3 face_normal(const Mesh& mesh, int f) {
  const auto& [a, b, c] = mesh.faces[f];
  const Vec3 p = mesh.vertices[a];
  return cross(mesh.vertices[b] - p, mesh.vertices[c] - p);
}

double face_area(const Mesh& mesh, int f) { return 0.5 * norm(face_normal(mesh, f)); }

double bounding_box_diagonal(const Mesh& mesh) {
  if (mesh.vertices.empty()) return 0;
  constexpr double inf = std::numeric_limits<double>::infinity();
  Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  for (const Vec3& v : mesh.vertices) {
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  return norm(hi - lo);
}

double median_edge_length(const Mesh& mesh) {
  std::vector<double> lengths;
  lengths.reserve(3 * mesh.faces.size());
  for (const auto& t : mesh.faces)
    for (int k = 0; k < 3; ++k)
      lengths.push_back(norm(mesh.vertices[t[(k + 1) % 3]] - mesh.vertices[t[k]]));
  if (lengths.empty()) return 0;
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  return lengths[lengths.size() / 2];
}

}  // namespace papernet
