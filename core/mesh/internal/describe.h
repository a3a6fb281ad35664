#pragma once

#include <cstddef>
#include <cstdio>
#include <string>

#include "core/mesh/mesh.h"

namespace papernet::mesh_detail {

/// "(x, y, z)": where vertex v is, for messages that name it.
inline std::string position(const Mesh& m, int v) {
  char buf[96];
  const Vec3 p = m.vertices[v];
  std::snprintf(buf, sizeof buf, "(%g, %g, %g)", p.x, p.y, p.z);
  return buf;
}

/// "1 edge", "3 edges".
inline std::string plural(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace papernet::mesh_detail
