#include "core/io/write_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "core/errors.h"
#include "core/io/json_text.h"

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

// The GLB file of glTF JSON `gltf` and binary chunk `bin` (padded to 4 bytes already).
std::string glb_container(const nlohmann::json& gltf, const std::string& bin) {
  std::string text = json_text(gltf);
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

// A material as paper shows it: not metallic, both sides.
nlohmann::json paper_material(const RGBA& base, int texture, AlphaMode mode, double cutoff,
                              const std::string& name) {
  using nlohmann::json;
  json pbr = json::object({{"baseColorFactor", json::array({base[0], base[1], base[2], base[3]})},
                           {"metallicFactor", 0},
                           {"roughnessFactor", 1}});
  if (texture >= 0) pbr["baseColorTexture"] = json::object({{"index", texture}});
  json m = json::object(
      {{"pbrMetallicRoughness", pbr}, {"alphaMode", alpha_mode_name(mode)}, {"doubleSided", true}});
  if (mode == AlphaMode::Mask) m["alphaCutoff"] = cutoff;
  if (!name.empty()) m["name"] = name;
  return m;
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
      {"meshes", json::array({{{"name", "folded"},
                               {"primitives", json::array({{{"attributes", {{"POSITION", 0}}},
                                                            {"indices", 1},
                                                            {"mode", 4},
                                                            {"material", 0}}})}}})},
      {"materials",
       json::array({paper_material({1, 1, 1, 1}, -1, AlphaMode::Opaque, 0.5, "paper")})},
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
  return glb_container(gltf, bin);
}

std::string write_glb(const Mesh& mesh, const MeshColour& colour) {
  if (colour.empty()) return write_glb(mesh);
  check_indices(mesh);
  if (mesh.faces.empty()) throw InvalidInputException("cannot write an empty mesh as GLB");
  const std::size_t nf = mesh.faces.size();
  const auto per_face = [&](std::size_t n, const char* what) {
    if (n != 0 && n != nf)
      throw InvalidInputException(std::string("the mesh's ") + what + " are for " +
                                  std::to_string(n) + " faces, not " + std::to_string(nf));
  };
  per_face(colour.uvs.size(), "texture coordinates");
  per_face(colour.colours.size(), "vertex colours");
  per_face(colour.face_materials.size(), "materials");
  const int materials = static_cast<int>(colour.materials.size());
  const auto material_of = [&](std::size_t f) {
    const int m = colour.face_materials.empty() ? -1 : colour.face_materials[f];
    return m >= 0 && m < materials ? m : -1;
  };

  using nlohmann::json;
  std::string bin;
  json views = json::array(), accessors = json::array();
  // A buffer view of what was appended to bin since `from`, padded to 4 bytes.
  const auto view = [&](std::size_t from, int target) {
    json v = json::object({{"buffer", 0}, {"byteOffset", from}, {"byteLength", bin.size() - from}});
    if (target) v["target"] = target;
    while (bin.size() % 4) bin.push_back('\0');
    views.push_back(v);
    return static_cast<int>(views.size()) - 1;
  };
  const auto accessor = [&](int view_index, std::size_t count, const char* type) {
    accessors.push_back(json::object(
        {{"bufferView", view_index}, {"componentType", 5126}, {"count", count}, {"type", type}}));
    return static_cast<int>(accessors.size()) - 1;
  };
  const auto finite = [](double v) { return std::isfinite(v); };

  // One primitive per material (faces without one last), each corner a vertex of its own.
  json primitives = json::array();
  bool unmaterialed = false;
  std::vector<std::vector<std::size_t>> by_material(materials + 1);  // the last: none
  for (std::size_t f = 0; f < nf; ++f) {
    const int m = material_of(f);
    by_material[m < 0 ? materials : m].push_back(f);
  }
  for (int m = 0; m <= materials; ++m) {
    const int material = m < materials ? m : -1;
    const std::vector<std::size_t>& faces = by_material[m];
    if (faces.empty()) continue;
    unmaterialed |= material < 0;
    json attributes = json::object();
    std::size_t from = bin.size();
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (std::size_t i = 0; i < faces.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const Vec3& v = mesh.vertices[mesh.faces[faces[i]][k]];
        const float p[3] = {static_cast<float>(v.x), static_cast<float>(v.y),
                            static_cast<float>(v.z)};
        for (int c = 0; c < 3; ++c) {
          lo[c] = i == 0 && k == 0 ? p[c] : std::min(lo[c], p[c]);
          hi[c] = i == 0 && k == 0 ? p[c] : std::max(hi[c], p[c]);
          put(bin, p[c]);
        }
      }
    attributes["POSITION"] = accessor(view(from, 34962), 3 * faces.size(), "VEC3");
    accessors.back()["min"] = json::array({lo[0], lo[1], lo[2]});
    accessors.back()["max"] = json::array({hi[0], hi[1], hi[2]});
    if (!colour.uvs.empty() && material >= 0 && colour.materials[material].texture >= 0) {
      from = bin.size();
      for (std::size_t f : faces)
        for (const UV& uv : colour.uvs[f])
          for (double c : uv) put(bin, static_cast<float>(finite(uv[0]) && finite(uv[1]) ? c : 0));
      attributes["TEXCOORD_0"] = accessor(view(from, 34962), 3 * faces.size(), "VEC2");
    }
    if (!colour.colours.empty()) {
      from = bin.size();
      for (std::size_t f : faces)
        for (const RGBA& rgba : colour.colours[f]) {
          const bool known = std::all_of(rgba.begin(), rgba.end(), finite);
          for (double c : rgba) put(bin, static_cast<float>(known ? std::clamp(c, 0.0, 1.0) : 1));
        }
      attributes["COLOR_0"] = accessor(view(from, 34962), 3 * faces.size(), "VEC4");
    }
    primitives.push_back(json::object({{"attributes", attributes},
                                       {"mode", 4},
                                       {"material", material >= 0 ? material : materials}}));
  }

  // The materials as paper shows them.
  json material_list = json::array();
  const int textures = static_cast<int>(colour.textures.size());
  for (const Material& m : colour.materials)
    material_list.push_back(paper_material(m.base_color, m.texture < textures ? m.texture : -1,
                                           m.alpha_mode, m.alpha_cutoff, m.name));
  if (unmaterialed)
    material_list.push_back(paper_material({1, 1, 1, 1}, -1, AlphaMode::Opaque, 0.5, ""));

  // The textures' images as they came, each with its sampler.
  json images = json::array(), samplers = json::array(), texture_list = json::array();
  for (int t = 0; t < textures; ++t) {
    const Texture& tex = colour.textures[t];
    const std::size_t from = bin.size();
    bin += tex.bytes;
    images.push_back(json::object({{"bufferView", view(from, 0)}, {"mimeType", tex.mime_type}}));
    json sampler = json::object({{"wrapS", tex.sampler.wrap_s}, {"wrapT", tex.sampler.wrap_t}});
    if (tex.sampler.mag_filter) sampler["magFilter"] = tex.sampler.mag_filter;
    if (tex.sampler.min_filter) sampler["minFilter"] = tex.sampler.min_filter;
    samplers.push_back(sampler);
    texture_list.push_back(json::object({{"sampler", t}, {"source", t}}));
  }

  json gltf = {
      {"asset", {{"version", "2.0"}, {"generator", "papernet"}}},
      {"scene", 0},
      {"scenes", json::array({{{"nodes", {0}}}})},
      {"nodes", json::array({{{"mesh", 0}, {"name", "folded"}}})},
      {"meshes", json::array({{{"name", "folded"}, {"primitives", primitives}}})},
      {"materials", material_list},
      {"buffers", json::array({{{"byteLength", bin.size()}}})},
      {"bufferViews", views},
      {"accessors", accessors},
  };
  if (textures > 0) {
    gltf["images"] = images;
    gltf["samplers"] = samplers;
    gltf["textures"] = texture_list;
  }
  return glb_container(gltf, bin);
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
