#pragma once
// Private to core/load*.cpp: the per-format readers and the unwelded mesh they produce.

#include <array>
#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/load.h"
#include "core/mesh/colour.h"
#include "core/vec.h"

namespace papernet::detail {

/// A triangle soup as a reader found it: positions as written, polygons already fanned.
struct RawMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> faces;
  bool triangulated = false;
  std::vector<std::string> notes;
  MeshColour colour;  ///< per face, as `faces` (docs/colour.md)
};

/// Adds triangle fans of `poly` to `out`, checking indices and the face limit.
/// \throw IOException when an index is out of range or the limit is passed.
void add_polygon(RawMesh& out, const std::vector<long long>& poly, const LoadOptions& options,
                 std::string_view where);

/// A texture from an image's bytes: decoded to check it (and learn its size), its bytes kept.
/// An image that is not PNG/JPEG or does not decode gives false and a note saying that `what`
/// is printed without it. \throw LimitExceededException over `options.max_image_pixels`.
bool make_texture(std::string name, std::string bytes, const LoadOptions& options,
                  const std::string& what, Texture& out, std::vector<std::string>& notes);

/// Throws IOException when `count` declared faces exceed the limit.
void check_declared_faces(std::size_t count, const LoadOptions& options, std::string_view what);

/// Throws IOException when `count` vertices (declared or read so far) exceed the limit.
void check_vertices(std::size_t count, const LoadOptions& options, std::string_view what);

RawMesh read_obj(std::string_view bytes, const LoadOptions& options);
RawMesh read_off(std::string_view bytes, const LoadOptions& options);
RawMesh read_stl(std::string_view bytes, const LoadOptions& options);
RawMesh read_ply(std::string_view bytes, const LoadOptions& options);
/// glTF JSON (`binary` false) or GLB container (`binary` true).
RawMesh read_gltf(std::string_view bytes, bool binary, const LoadOptions& options);
/// A raw Draco stream (.drc or the payload of KHR_draco_mesh_compression). Refuses point clouds
/// and headers that declare more faces or points than the limits or the stream can hold.
/// `position_id` is the unique id of the position attribute (glTF names it), or -1 for the
/// attribute Draco marks as POSITION; every id in `required_ids` must exist too.
RawMesh read_draco(std::string_view bytes, const LoadOptions& options, int position_id = -1,
                   const std::vector<int>& required_ids = {});

}  // namespace papernet::detail

namespace papernet::detail {

/// Draco primitives of a glTF, decoded by read_draco(), keyed by (mesh, primitive).
using DracoPrimitives = std::map<std::pair<int, int>, RawMesh>;

/// Checks and decodes every KHR_draco_mesh_compression primitive of a glTF's JSON before
/// tinygltf parses it. tinygltf's own Draco hook indexes accessors, buffer views and attributes
/// without bounds checks; after this pass every index it will follow is known to be valid and
/// every stream to decode within the limits. `glb_bin` is the GLB's BIN chunk (empty for .gltf).
/// \throw IOException naming the fault.
/// tinygltf's URI helpers (defined next to its implementation, in load_gltf.cpp).
std::string url_decode(const std::string& uri);
bool is_data_uri(const std::string& uri);
std::string decode_base64(const std::string& text);
bool decode_data_uri(const std::string& uri, std::vector<unsigned char>& out);

/// Parses glTF JSON into a DOM, refusing (IOException) more than `max_values` values or nesting
/// deeper than 64 before the DOM grows past that; a syntax error gives a discarded value.
nlohmann::json parse_gltf_json(std::string_view json, std::size_t max_values = 2'000'000);

DracoPrimitives predecode_gltf_draco(std::string_view json, std::string_view glb_bin,
                                     const LoadOptions& options);

}  // namespace papernet::detail
