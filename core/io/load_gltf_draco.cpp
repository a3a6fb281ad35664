// The Draco pre-pass of the glTF reader (see predecode_gltf_draco in load_formats.h).
#include <cstdint>

#include "core/errors.h"
#include "core/io/internal/load_formats.h"

namespace papernet::detail {
namespace {

using Json = nlohmann::json;

std::size_t get_index(const Json& object, const char* key, std::size_t size,
                      const std::string& what) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number_integer() || it->get<long long>() < 0 ||
      std::size_t(it->get<long long>()) >= size)
    throw IOException("gltf: " + what + " refers to a missing " + key);
  return std::size_t(it->get<long long>());
}

// The accessor a Draco primitive decodes into must have one of glTF's component types: tinygltf
// sizes the decoded buffer by it before it checks anything, and an unknown type (size -1) turns
// that size into about 4 GB.
void check_component_type(const Json& accessors, std::size_t index, const std::string& what) {
  const Json& a = accessors[index];
  const auto it = a.is_object() ? a.find("componentType") : a.end();
  const long long type = it != a.end() && it->is_number_integer() ? it->get<long long>() : 0;
  if (type < 5120 || type > 5126 || type == 5124)
    throw IOException("gltf: " + what + ": accessor " + std::to_string(index) +
                      " has no valid componentType (5120-5123, 5125 or 5126)");
}

std::uint64_t get_size(const Json& object, const char* key, std::uint64_t fallback) {
  const auto it = object.find(key);
  if (it == object.end()) return fallback;
  if (!it->is_number_unsigned()) throw IOException(std::string("gltf: bad ") + key);
  return it->get<std::uint64_t>();
}

/// The bytes of buffer `index`, from the GLB chunk, a data URI or the supplied external files.
std::string buffer_bytes(const Json& buffers, std::size_t index, std::string_view glb_bin,
                         const LoadOptions& options) {
  const Json& b = buffers[index];
  const std::uint64_t length = get_size(b, "byteLength", 0);
  const auto uri = b.find("uri");
  std::string data;
  if (uri == b.end()) {
    if (index != 0 || glb_bin.empty())
      throw IOException("gltf: buffer " + std::to_string(index) + " has no data");
    data = glb_bin;
  } else if (!uri->is_string()) {
    throw IOException("gltf: buffer " + std::to_string(index) + " has a bad uri");
  } else if (is_data_uri(uri->get<std::string>())) {
    std::vector<unsigned char> decoded;
    if (!decode_data_uri(uri->get<std::string>(), decoded))
      throw IOException("gltf: buffer " + std::to_string(index) + " has a bad data URI");
    data.assign(decoded.begin(), decoded.end());
  } else {
    const std::string name = url_decode(uri->get<std::string>());
    const auto it = options.external_files.find(name);
    if (it == options.external_files.end())
      throw IOException("gltf: external buffer '" + name +
                        "' was not supplied with the file (only files uploaded with it are read)");
    data = it->second;
  }
  if (data.size() < length)
    throw IOException("gltf: buffer " + std::to_string(index) + " declares " +
                      std::to_string(length) + " bytes but has " + std::to_string(data.size()));
  return data;
}

// A SAX pass that only counts: values against the limit, nesting against 64 levels. nlohmann's
// parse callback cannot do this job: its DOM builder scans the parent's members after every
// object it keeps, which is quadratic (a 1 MB glTF with 50,000 nodes took minutes).
struct JsonGuard {
  std::size_t max_values;
  std::size_t values = 0;
  int depth = 0;
  bool syntax_error = false;

  bool value() {
    if (++values > max_values)
      throw IOException("gltf: the JSON has more than " + std::to_string(max_values) + " values");
    return true;
  }
  bool open() {
    if (++depth > 64) throw IOException("gltf: the JSON nests deeper than 64 levels");
    return value();
  }
  bool null() { return value(); }
  bool boolean(bool) { return value(); }
  bool number_integer(Json::number_integer_t) { return value(); }
  bool number_unsigned(Json::number_unsigned_t) { return value(); }
  bool number_float(Json::number_float_t, const Json::string_t&) { return value(); }
  bool string(Json::string_t&) { return value(); }
  bool binary(Json::binary_t&) { return value(); }
  bool start_object(std::size_t) { return open(); }
  bool key(Json::string_t&) { return true; }
  bool end_object() { return --depth, true; }
  bool start_array(std::size_t) { return open(); }
  bool end_array() { return --depth, true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) {
    syntax_error = true;
    return false;
  }
};

}  // namespace

Json parse_gltf_json(std::string_view json, std::size_t max_values) {
  // Real glTF JSON holds thousands of values (buffers are binary or one base64 string each);
  // a DOM costs tens of bytes per value, so a flood of tiny values is refused before the DOM
  // is built, by a first pass that only counts.
  JsonGuard guard{max_values};
  if (!Json::sax_parse(json, &guard) || guard.syntax_error) return Json(Json::value_t::discarded);
  return Json::parse(json, nullptr, false);
}

DracoPrimitives predecode_gltf_draco(std::string_view json, std::string_view glb_bin,
                                     const LoadOptions& options) {
  DracoPrimitives out;
  const Json doc = parse_gltf_json(json);
  if (doc.is_discarded() || !doc.is_object()) return out;  // tinygltf reports the syntax error
  const auto meshes = doc.find("meshes");
  if (meshes == doc.end() || !meshes->is_array()) return out;
  static const Json kEmpty = Json::array();
  auto array = [&](const char* key) -> const Json& {
    const auto it = doc.find(key);
    return it != doc.end() && it->is_array() ? *it : kEmpty;
  };
  const Json &accessors = array("accessors"), &views = array("bufferViews"),
             &buffers = array("buffers");
  std::size_t faces = 0;
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const Json& mesh = (*meshes)[m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
      continue;
    const Json& prims = mesh["primitives"];
    for (std::size_t p = 0; p < prims.size(); ++p) {
      const Json& prim = prims[p];
      if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object() ||
          !prim["extensions"].contains("KHR_draco_mesh_compression"))
        continue;
      const std::string what = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      const Json& ext = prim["extensions"]["KHR_draco_mesh_compression"];
      if (!ext.is_object()) throw IOException("gltf: " + what + ": bad Draco extension");
      const std::size_t vi = get_index(ext, "bufferView", views.size(), what);
      const Json& view = views[vi];
      const std::size_t bi = get_index(view, "buffer", buffers.size(), "buffer view");
      const std::uint64_t offset = get_size(view, "byteOffset", 0);
      const std::uint64_t length = get_size(view, "byteLength", 0);
      const std::uint64_t buffer_length = get_size(buffers[bi], "byteLength", 0);
      if (offset > buffer_length || length > buffer_length - offset)
        throw IOException("gltf: Draco buffer view " + std::to_string(vi) +
                          " lies outside its buffer");
      if (prim.contains("indices"))
        check_component_type(accessors, get_index(prim, "indices", accessors.size(), what), what);
      const Json& attributes = prim.contains("attributes") ? prim["attributes"] : kEmpty;
      const auto draco_attributes = ext.find("attributes");
      if (draco_attributes == ext.end() || !draco_attributes->is_object())
        throw IOException("gltf: " + what + ": Draco extension without attributes");
      std::vector<int> ids;
      for (const auto& [name, id] : draco_attributes->items()) {
        if (!attributes.is_object()) throw IOException("gltf: " + what + " has no attributes");
        check_component_type(accessors, get_index(attributes, name.c_str(), accessors.size(), what),
                             what);
        if (!id.is_number_integer() || id.get<long long>() < 0)
          throw IOException("gltf: " + what + ": bad Draco attribute id for " + name);
        ids.push_back(id.get<int>());
      }
      const auto position = draco_attributes->find("POSITION");
      if (position == draco_attributes->end())
        throw IOException("gltf: " + what + ": Draco extension without POSITION");
      const int mode =
          prim.contains("mode") && prim["mode"].is_number_integer() ? prim["mode"].get<int>() : 4;
      const std::string data = buffer_bytes(buffers, bi, glb_bin, options);
      LoadOptions left = options;
      left.max_faces = options.max_faces - std::min(faces, options.max_faces);
      RawMesh decoded;
      try {
        decoded = read_draco(std::string_view(data).substr(offset, length), left,
                             position->get<int>(), ids);  // tinygltf dereferences every id
      } catch (const IOException& e) {
        // A point cloud under a POINTS/LINES primitive: draco refuses to decode it as a mesh
        // before allocating, and the reader names the mode it skips. Anything else is fatal.
        const bool triangles = mode == 4 || mode == 5 || mode == 6;
        if (triangles || std::string(e.what()).find("point cloud") == std::string::npos) throw;
        continue;
      }
      faces += decoded.faces.size();
      out.emplace(std::make_pair(int(m), int(p)), std::move(decoded));
    }
  }
  return out;
}

}  // namespace papernet::detail
