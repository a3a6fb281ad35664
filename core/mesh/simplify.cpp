#include "core/mesh/simplify.h"

namespace papernet {

std::optional<Mesh> simplify_mesh(const Mesh& mesh, CollapseStrategy strategy, std::size_t faces,
                                  Progress& progress) {
  if (faces == 0 || faces >= mesh.faces.size()) return std::nullopt;
  Mesh simple = decimate(mesh, {strategy, faces}, progress).compact();
  if (simple.faces.size() >= mesh.faces.size()) return std::nullopt;
  return simple;
}

}  // namespace papernet
