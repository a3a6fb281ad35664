#include "core/mesh/mesh.h"

#include <algorithm>
#include <vector>

namespace papernet {

Vec3 face_normal(const Mesh& mesh, int f) {
  const auto& [a, b, c] = mesh.faces[f];
  const Vec3 p = mesh.vertices[a];
  return cross(mesh.vertices[b] - p, mesh.vertices[c] - p);
}

double face_area(const Mesh& mesh, int f) { return 0.5 * norm(face_normal(mesh, f)); }

Mesh mesh_of_faces(const Mesh& mesh, const std::vector<int>& faces) {
  Mesh out;
  std::vector<int> index(mesh.vertices.size(), -1);
  for (int f : faces) {
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k) {
      int& i = index[mesh.faces[f][k]];
      if (i < 0) {
        i = static_cast<int>(out.vertices.size());
        out.vertices.push_back(mesh.vertices[mesh.faces[f][k]]);
      }
      t[k] = i;
    }
    out.faces.push_back(t);
  }
  return out;
}

Box3 bounding_box(const Mesh& mesh) {
  Box3 box = Box3::empty();
  for (const Vec3& v : mesh.vertices) box.add(v);
  return box;
}

double bounding_box_diagonal(const Mesh& mesh) {
  return mesh.vertices.empty() ? 0 : norm(bounding_box(mesh).size());
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
