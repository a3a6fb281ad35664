// glTF 2.0 (.gltf JSON, .glb) through tinygltf. KHR_draco_mesh_compression primitives are
// checked and decoded by predecode_gltf_draco() first (tinygltf's own Draco hook follows indices
// unchecked and decodes before any limit applies), and their faces come from that decode.
// File access goes through FsCallbacks that serve only LoadOptions::external_files: no path a
// glTF names is ever opened.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_ENABLE_DRACO
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
#undef TINYGLTF_IMPLEMENTATION  // the colour reader's header includes it again, for declarations

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_set>

#include "core/errors.h"
#include "core/io/image.h"
#include "core/io/internal/gltf_colour.h"
#include "core/io/internal/load_formats.h"

namespace papernet {
namespace detail {
namespace {

using Matrix = std::array<double, 16>;  // column-major, as glTF writes it
constexpr Matrix kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Matrix multiply(const Matrix& a, const Matrix& b) {
  Matrix r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row)
      for (int k = 0; k < 4; ++k) r[c * 4 + row] += a[k * 4 + row] * b[c * 4 + k];
  return r;
}

Matrix local_matrix(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    Matrix m;
    std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
    return m;
  }
  Matrix t = kIdentity, r = kIdentity, s = kIdentity;
  if (node.translation.size() == 3)
    for (int i = 0; i < 3; ++i) t[12 + i] = node.translation[i];
  if (node.rotation.size() == 4) {
    const double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2],
                 w = node.rotation[3];
    r = {1 - 2 * (y * y + z * z),
         2 * (x * y + z * w),
         2 * (x * z - y * w),
         0,
         2 * (x * y - z * w),
         1 - 2 * (x * x + z * z),
         2 * (y * z + x * w),
         0,
         2 * (x * z + y * w),
         2 * (y * z - x * w),
         1 - 2 * (x * x + y * y),
         0,
         0,
         0,
         0,
         1};
  }
  if (node.scale.size() == 3)
    for (int i = 0; i < 3; ++i) s[i * 5] = node.scale[i];
  return multiply(t, multiply(r, s));
}

Vec3 transform(const Matrix& m, const Vec3& p) {
  return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12],
          m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
          m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
}

double determinant3(const Matrix& m) {
  return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
         m[8] * (m[1] * m[6] - m[5] * m[2]);
}

std::string mode_name(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return "POINTS";
    case TINYGLTF_MODE_LINE:
      return "LINES";
    case TINYGLTF_MODE_LINE_LOOP:
      return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP:
      return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLES:
      return "TRIANGLES";
    case TINYGLTF_MODE_TRIANGLE_STRIP:
      return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN:
      return "TRIANGLE_FAN";
  }
  return "mode " + std::to_string(mode);
}

/// Where an accessor's elements are, checked against its buffer view and buffer before any
/// element is read or anything is allocated for them.
struct View {
  const unsigned char* data = nullptr;
  std::size_t count = 0, stride = 0;
};

View accessor_view(const tinygltf::Model& model, int index, std::size_t element_size,
                   const std::string& what) {
  if (index < 0 || std::size_t(index) >= model.accessors.size())
    throw IOException("gltf: " + what + " accessor " + std::to_string(index) + " does not exist");
  const tinygltf::Accessor& a = model.accessors[index];
  if (a.sparse.isSparse) throw IOException("gltf: sparse " + what + " accessors are not supported");
  if (a.bufferView < 0 || std::size_t(a.bufferView) >= model.bufferViews.size())
    throw IOException("gltf: " + what + " accessor " + std::to_string(index) +
                      " has no buffer view");
  const tinygltf::BufferView& bv = model.bufferViews[a.bufferView];
  if (bv.buffer < 0 || std::size_t(bv.buffer) >= model.buffers.size())
    throw IOException("gltf: buffer view " + std::to_string(a.bufferView) + " has no buffer");
  const auto& buffer = model.buffers[bv.buffer].data;
  if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset)
    throw IOException("gltf: buffer view " + std::to_string(a.bufferView) +
                      " lies outside its buffer");
  View v;
  v.count = a.count;
  v.stride = bv.byteStride ? bv.byteStride : element_size;
  if (a.count == 0) return v;
  // (count-1)*stride + offset + element must fit the view: this bounds count by the view's
  // bytes, so an accessor cannot claim more elements than its data holds.
  const std::uint64_t need = std::uint64_t{a.byteOffset} + element_size +
                             std::uint64_t{v.stride} * (std::uint64_t{a.count} - 1);
  if (v.stride < element_size || a.count > bv.byteLength || need > bv.byteLength)
    throw IOException("gltf: " + what + " accessor " + std::to_string(index) + " declares " +
                      std::to_string(a.count) + " elements but its buffer view has " +
                      std::to_string(bv.byteLength) + " bytes");
  v.data = buffer.data() + bv.byteOffset + a.byteOffset;
  return v;
}

constexpr unsigned char kZeros[4] = {};  // a component of any type, to ask for its type

std::vector<Vec3> read_positions(const tinygltf::Model& model, int index) {
  if (index < 0 || std::size_t(index) >= model.accessors.size())
    throw IOException("gltf: a primitive has no POSITION accessor");
  const tinygltf::Accessor& a = model.accessors[index];
  if (a.type != TINYGLTF_TYPE_VEC3) throw IOException("gltf: POSITION is not a VEC3 accessor");
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  if (size <= 0 || size > 4) throw IOException("gltf: bad POSITION component type");
  if (std::isnan(gltf_component(kZeros, a.componentType, false)))
    throw IOException("gltf: unsupported position component type " +
                      std::to_string(a.componentType));
  const View v = accessor_view(model, index, 3 * std::size_t(size), "POSITION");
  std::vector<Vec3> out(v.count);
  for (std::size_t i = 0; i < v.count; ++i) {
    const unsigned char* p = v.data + i * v.stride;
    out[i] = {gltf_component(p, a.componentType, a.normalized),
              gltf_component(p + size, a.componentType, a.normalized),
              gltf_component(p + 2 * size, a.componentType, a.normalized)};
  }
  return out;
}

std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int index) {
  if (index < 0 || std::size_t(index) >= model.accessors.size())
    throw IOException("gltf: indices accessor " + std::to_string(index) + " does not exist");
  const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
  if (a.type != TINYGLTF_TYPE_SCALAR) throw IOException("gltf: indices are not SCALAR");
  const int type = a.componentType;
  const std::size_t size = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                           : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                           : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                            : 0;
  if (size == 0) throw IOException("gltf: indices must be unsigned byte, short or int");
  const View v = accessor_view(model, index, size, "indices");
  std::vector<std::uint32_t> out(v.count);
  for (std::size_t i = 0; i < v.count; ++i) {
    std::uint32_t x = 0;
    std::memcpy(&x, v.data + i * v.stride, size);  // little endian: the low bytes come first
    out[i] = x;
  }
  return out;
}

struct Collector {
  const tinygltf::Model& model;
  const LoadOptions& options;
  DracoPrimitives& draco;
  RawMesh out;
  std::vector<std::string> refused_modes;
  std::size_t strip_degenerates = 0;
  std::size_t dangling_indices = 0;

  void primitive(int mesh, int index, const Matrix& world) {
    const tinygltf::Primitive& prim = model.meshes[mesh].primitives[index];
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode < TINYGLTF_MODE_TRIANGLES || mode > TINYGLTF_MODE_TRIANGLE_FAN) {
      const std::string name = mode_name(mode);
      if (std::find(refused_modes.begin(), refused_modes.end(), name) == refused_modes.end())
        refused_modes.push_back(name);
      return;
    }
    std::vector<Vec3> positions;
    std::vector<std::uint32_t> indices;
    const auto draco_mesh = draco.find({mesh, index});
    if (draco_mesh != draco.end()) {
      positions = draco_mesh->second.vertices;
      for (const auto& f : draco_mesh->second.faces)
        indices.insert(indices.end(), f.begin(), f.end());
      if (mode != TINYGLTF_MODE_TRIANGLES)
        throw IOException("gltf: a Draco primitive with mode " + mode_name(mode));
    } else {
      const auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) throw IOException("gltf: a primitive has no POSITION");
      positions = read_positions(model, pos->second);
      if (prim.indices >= 0) {
        indices = read_indices(model, prim.indices);
      } else {
        indices.resize(positions.size());
        for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = std::uint32_t(i);
      }
    }
    const std::size_t n = indices.size();
    const std::size_t triangles = mode == TINYGLTF_MODE_TRIANGLES ? n / 3 : (n >= 3 ? n - 2 : 0);
    check_declared_faces(out.faces.size() + triangles, options, "the glTF");
    if (mode == TINYGLTF_MODE_TRIANGLES && n % 3 != 0) ++dangling_indices;
    for (std::uint32_t i : indices)
      if (i >= positions.size())
        throw IOException("gltf: index " + std::to_string(i) + " out of range (" +
                          std::to_string(positions.size()) + " positions)");
    // Instances copy positions: the limit bounds what a small file can make us allocate.
    check_vertices(out.vertices.size() + positions.size(), options, "the glTF");
    const int base = static_cast<int>(out.vertices.size());
    for (const Vec3& p : positions) out.vertices.push_back(transform(world, p));
    // A mirroring transform turns counter-clockwise faces clockwise: swap two corners back.
    const bool flip = determinant3(world) < 0;
    const std::size_t faces_before = out.faces.size();
    std::vector<std::array<std::uint32_t, 3>> corners;  // of this primitive's faces
    auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, bool strip) {
      if (strip && (a == b || b == c || a == c)) {
        ++strip_degenerates;  // strips use repeated indices to restart; no face is meant
        return;
      }
      if (flip) std::swap(b, c);
      out.faces.push_back({base + int(a), base + int(b), base + int(c)});
      corners.push_back({a, b, c});
    };
    if (mode != TINYGLTF_MODE_TRIANGLES) out.triangulated = true;
    for (std::size_t i = 0; i < triangles; ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLES)
        add(indices[3 * i], indices[3 * i + 1], indices[3 * i + 2], false);
      else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
        add(indices[i], indices[i + 1 + i % 2], indices[i + 2 - i % 2], true);
      else
        add(indices[i + 1], indices[i + 2], indices[0], true);
    }
    const MeshColour colour = read_gltf_primitive_colour(model, prim, corners, positions.size());
    append_faces(out.colour, faces_before, colour, corners.size());
  }

  /// Every node under `root`, depth first in file order. A loop with its own stack: a hostile
  /// file chains hundreds of thousands of nodes, which recursion would follow off the stack.
  void nodes(int root, std::unordered_set<int>& seen) {
    std::vector<std::pair<int, Matrix>> stack{{root, kIdentity}};
    while (!stack.empty()) {
      const auto [index, parent] = stack.back();
      stack.pop_back();
      if (index < 0 || std::size_t(index) >= model.nodes.size())
        throw IOException("gltf: node " + std::to_string(index) + " does not exist");
      if (!seen.insert(index).second) continue;  // glTF forbids cycles and shared nodes
      const tinygltf::Node& n = model.nodes[index];
      const Matrix world = multiply(parent, local_matrix(n));
      if (n.mesh >= 0) {
        if (std::size_t(n.mesh) >= model.meshes.size())
          throw IOException("gltf: mesh " + std::to_string(n.mesh) + " does not exist");
        for (std::size_t p = 0; p < model.meshes[n.mesh].primitives.size(); ++p)
          primitive(n.mesh, int(p), world);
      }
      for (auto child = n.children.rbegin(); child != n.children.rend(); ++child)
        stack.emplace_back(*child, world);
    }
  }
};

bool fs_file_exists(const std::string& path, void* user) {
  const auto& files = *static_cast<const std::map<std::string, std::string>*>(user);
  return files.count(path.starts_with("./") ? path.substr(2) : path) > 0;
}
std::string fs_expand(const std::string& path, void*) { return path; }
bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
             void* user) {
  const auto& files = *static_cast<const std::map<std::string, std::string>*>(user);
  const auto it = files.find(path.starts_with("./") ? path.substr(2) : path);
  if (it == files.end()) {
    *err = "not supplied with the upload";
    return false;
  }
  out->assign(it->second.begin(), it->second.end());
  return true;
}
bool fs_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  *err = "writing is disabled";
  return false;
}
// Keeps the bytes of an image tinygltf decoded from a data URI; they are decoded (and checked)
// by read_gltf_materials, which knows the limits. An image in a buffer view is left to
// read_gltf_materials too: tinygltf hands it over without checking that the view lies inside
// its buffer.
bool keep_image(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                const unsigned char* bytes, int size, void* user) {
  auto& images = *static_cast<GltfImageBytes*>(user);
  if (image->bufferView < 0 && bytes && size > 0)
    images[index].assign(reinterpret_cast<const char*>(bytes), std::size_t(size));
  return true;
}

/// Checks the GLB container before tinygltf parses it, so that its lengths are trusted.
/// Returns the JSON and BIN chunks.
std::pair<std::string_view, std::string_view> check_glb(std::string_view bytes) {
  if (bytes.size() < 20) throw IOException("glb: shorter than its 20-byte header");
  std::uint32_t header[5];
  std::memcpy(header, bytes.data(), 20);
  if (header[1] == 1) throw IOException("glb: glTF 1.0 binary files are not supported");
  if (header[1] != 2) throw IOException("glb: unknown version " + std::to_string(header[1]));
  if (header[2] > bytes.size())
    throw IOException("glb: the header declares " + std::to_string(header[2]) +
                      " bytes but the file has " + std::to_string(bytes.size()));
  if (header[3] > header[2] - 20 || header[4] != 0x4E4F534A)
    throw IOException("glb: the JSON chunk is missing or longer than the file");
  const std::string_view json = bytes.substr(20, header[3]);
  std::string_view bin;
  const std::size_t next = 20 + ((std::size_t{header[3]} + 3) & ~std::size_t{3});
  if (next + 8 <= header[2]) {
    std::uint32_t chunk[2];
    std::memcpy(chunk, bytes.data() + next, 8);
    if (chunk[1] == 0x004E4942 && chunk[0] <= header[2] - next - 8)
      bin = bytes.substr(next + 8, chunk[0]);
  }
  return {json, bin};
}

}  // namespace

RawMesh read_gltf(std::string_view bytes, bool binary, const LoadOptions& options) {
  std::string_view json = bytes, bin;
  if (binary) std::tie(json, bin) = check_glb(bytes);
  DracoPrimitives draco = predecode_gltf_draco(json, bin, options);
  tinygltf::TinyGLTF parser;
  tinygltf::FsCallbacks fs{
      &fs_file_exists, &fs_expand, &fs_read, &fs_write,
      const_cast<std::map<std::string, std::string>*>(&options.external_files)};
  parser.SetFsCallbacks(fs);
  GltfImageBytes images;
  parser.SetImageLoader(&keep_image, &images);
  tinygltf::Model model;
  std::string err, warn;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const bool ok = binary ? parser.LoadBinaryFromMemory(&model, &err, &warn, data,
                                                       static_cast<unsigned>(bytes.size()), "")
                         : parser.LoadASCIIFromString(&model, &err, &warn, bytes.data(),
                                                      static_cast<unsigned>(bytes.size()), "");
  if (!ok) {
    while (!err.empty() && err.back() == '\n') err.pop_back();
    if (err.find("File not found") != std::string::npos ||
        err.find("File read error") != std::string::npos)
      throw IOException(
          "gltf: an external buffer was not supplied with the file (only buffers "
          "uploaded with it are read): " +
          err);
    throw IOException("gltf: " + (err.empty() ? std::string("cannot parse") : err));
  }
  if (model.asset.version.empty() || model.asset.version[0] != '2')
    throw IOException("gltf: version '" + model.asset.version + "' is not glTF 2.0");
  for (const std::string& ext : model.extensionsRequired)
    if (ext.find("meshopt") != std::string::npos)
      throw IOException("gltf: required extension " + ext + " is not supported");

  Collector c{model, options, draco, {}, {}, 0, 0};
  read_gltf_materials(model, images, options, c.out.colour, c.out.notes);
  std::unordered_set<int> seen;
  if (!model.scenes.empty()) {
    const int scene =
        model.defaultScene >= 0 && std::size_t(model.defaultScene) < model.scenes.size()
            ? model.defaultScene
            : 0;
    for (int root : model.scenes[scene].nodes) c.nodes(root, seen);
  } else {
    for (std::size_t m = 0; m < model.meshes.size(); ++m)
      for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p)
        c.primitive(int(m), int(p), kIdentity);
  }
  if (c.out.faces.empty() && !c.refused_modes.empty()) {
    std::string modes;
    for (const auto& m : c.refused_modes) modes += (modes.empty() ? "" : ", ") + m;
    throw IOException("gltf: no triangle primitives, only " + modes +
                      " (papernet unfolds triangle meshes)");
  }
  for (const auto& m : c.refused_modes) c.out.notes.push_back(m + " primitives were skipped");
  if (c.strip_degenerates)
    c.out.notes.push_back(std::to_string(c.strip_degenerates) +
                          " degenerate strip/fan triangles (restarts) were skipped");
  if (c.dangling_indices)
    c.out.notes.push_back("trailing indices that do not form a whole triangle were ignored");
  return std::move(c.out);
}

std::string url_decode(const std::string& uri) { return tinygltf::dlib::urldecode(uri); }
bool is_data_uri(const std::string& uri) { return tinygltf::IsDataURI(uri); }
std::string decode_base64(const std::string& text) { return tinygltf::base64_decode(text); }
bool decode_data_uri(const std::string& uri, std::vector<unsigned char>& out) {
  std::string mime;
  return tinygltf::DecodeDataURI(&out, mime, uri, 0, false);
}

}  // namespace detail

std::vector<std::string> gltf_external_uris(std::string_view gltf_json) {
  const nlohmann::json doc = detail::parse_gltf_json(gltf_json);
  if (doc.is_discarded() || !doc.is_object()) throw IOException("gltf: not JSON");
  std::vector<std::string> uris;
  const auto buffers = doc.find("buffers");
  if (buffers == doc.end() || !buffers->is_array()) return uris;
  for (const auto& b : *buffers) {
    if (!b.is_object()) continue;
    const auto u = b.find("uri");
    if (u == b.end() || !u->is_string()) continue;
    // Decoded the way tinygltf decodes it before asking for the file.
    const std::string uri = tinygltf::dlib::urldecode(u->get<std::string>());
    if (!tinygltf::IsDataURI(uri)) uris.push_back(uri);
  }
  // Images (textures) too: a missing one only costs its material's texture.
  const auto images = doc.find("images");
  if (images == doc.end() || !images->is_array()) return uris;
  for (const auto& i : *images) {
    if (!i.is_object()) continue;
    const auto u = i.find("uri");
    if (u == i.end() || !u->is_string()) continue;
    const std::string uri = tinygltf::dlib::urldecode(u->get<std::string>());
    if (!tinygltf::IsDataURI(uri)) uris.push_back(uri);
  }
  return uris;
}

std::string encode_base64(std::string_view bytes) {
  return tinygltf::base64_encode(reinterpret_cast<const unsigned char*>(bytes.data()),
                                 static_cast<unsigned int>(bytes.size()));
}

}  // namespace papernet
