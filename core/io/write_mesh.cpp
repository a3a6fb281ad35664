#include "core/io/write_mesh.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/errors.h"

namespace papernet {

namespace {

void check_indices(const Mesh& mesh) {
  const auto n = static_cast<int>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int v : mesh.faces[f])
      if (v < 0 || v >= n)
        throw InvalidInputException("face " + std::to_string(f) + " refers to vertex " +
                                    std::to_string(v) + " of " + std::to_string(n));
}

template <class T>
void put(std::string& out, T value) {
  char buf[sizeof(T)];
  std::memcpy(buf, &value, sizeof(T));  // GLB is little-endian, as are the hosts we build for
  out.append(buf, sizeof(T));
}

}  // namespace

std::string write_glb(const Mesh& mesh) {
  check_indices(mesh);
  if (mesh.faces.empty()) throw InvalidInputException("cannot write an empty mesh as GLB");
  std::string bin;
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const float p[3] = {static_cast<float>(mesh.vertices[i].x),
                        static_cast<float>(mesh.vertices[i].y),
                        static_cast<float>(mesh.vertices[i].z)};
    for (int k = 0; k < 3; ++k) {
      lo[k] = i == 0 ? p[k] : std::min(lo[k], p[k]);
      hi[k] = i == 0 ? p[k] : std::max(hi[k], p[k]);
      put(bin, p[k]);
    }
  }
  const std::size_t positions_bytes = bin.size();
  for (const auto& f : mesh.faces)
    for (int v : f) put(bin, static_cast<std::uint32_t>(v));
  const std::size_t indices_bytes = bin.size() - positions_bytes;
  while (bin.size() % 4) bin.push_back('\0');

  using nlohmann::json;
  json gltf = {
      {"asset", {{"version", "2.0"}, {"generator", "papernet"}}},
      {"scene", 0},
      {"scenes", json::array({{{"nodes", {0}}}})},
      {"nodes", json::array({{{"mesh", 0}, {"name", "folded"}}})},
      {"meshes",
       json::array(
           {{{"name", "folded"},
             {"primitives",
              json::array({{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"mode", 4}}})}}})},
      {"buffers", json::array({{{"byteLength", bin.size()}}})},
      {"bufferViews",
       json::array(
           {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", positions_bytes}, {"target", 34962}},
            {{"buffer", 0},
             {"byteOffset", positions_bytes},
             {"byteLength", indices_bytes},
             {"target", 34963}}})},
      {"accessors", json::array({{{"bufferView", 0},
                                  {"componentType", 5126},
                                  {"count", mesh.vertices.size()},
                                  {"type", "VEC3"},
                                  {"min", {lo[0], lo[1], lo[2]}},
                                  {"max", {hi[0], hi[1], hi[2]}}},
                                 {{"bufferView", 1},
                                  {"componentType", 5125},
                                  {"count", 3 * mesh.faces.size()},
                                  {"type", "SCALAR"}}})},
  };
  std::string text = gltf.dump();
  while (text.size() % 4) text.push_back(' ');

  std::string out;
  const bool has_bin = !bin.empty();
  const std::size_t total = 12 + 8 + text.size() + (has_bin ? 8 + bin.size() : 0);
  if (total > std::numeric_limits<std::uint32_t>::max())
    throw InvalidInputException("mesh too large for a GLB file (over 4 GiB)");
  put(out, std::uint32_t{0x46546C67});  // "glTF"
  put(out, std::uint32_t{2});
  put(out, static_cast<std::uint32_t>(total));
  put(out, static_cast<std::uint32_t>(text.size()));
  put(out, std::uint32_t{0x4E4F534A});  // "JSON"
  out += text;
  if (has_bin) {
    put(out, static_cast<std::uint32_t>(bin.size()));
    put(out, std::uint32_t{0x004E4942});  // "BIN\0"
    out += bin;
  }
  return out;
}

std::string write_obj(const Mesh& mesh) {
  check_indices(mesh);
  std::ostringstream o;
  o.precision(9);
  o << "# papernet: the mesh the net folds into\n";
  for (const Vec3& v : mesh.vertices) o << "v " << v.x << ' ' << v.y << ' ' << v.z << '\n';
  for (const auto& f : mesh.faces)
    o << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
  return o.str();
}

}  // namespace papernet
