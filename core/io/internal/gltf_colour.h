#pragma once
// Private to core/io/load_gltf*.cpp: a glTF's colour (texture coordinates, vertex colours,
// materials and their textures), read next to its geometry (docs/colour.md).

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/io/load.h"
#include "core/mesh/colour.h"

namespace papernet::detail {

/// One component of a glTF accessor's element at `p`: float, or a (normalized) integer of 8 or
/// 16 bits (glTF 2.0 §3.11). NaN for another component type; the caller says what that means
/// (positions refuse it, colour data are dropped).
double gltf_component(const unsigned char* p, int type, bool normalized);

/// Image bytes tinygltf decoded from a data URI and handed to its image loader, by image.
using GltfImageBytes = std::map<int, std::string>;

/// The model's materials and the textures they use; images come from their buffer view, else
/// from `images`, else from `options.external_files` by URI. An image that is missing, outside
/// its buffer, not PNG/JPEG or does not decode leaves its material without a texture and adds a
/// note.
/// \throw LimitExceededException when an image has more pixels than the limit.
void read_gltf_materials(const tinygltf::Model& model, const GltfImageBytes& images,
                         const LoadOptions& options, MeshColour& colour,
                         std::vector<std::string>& notes);

/// Per-corner texture coordinates (the set the primitive's material samples, with its
/// KHR_texture_transform applied), COLOR_0 and the material of `faces` (corner indices into the
/// primitive's vertices, already in the order the mesh keeps) as a MeshColour of faces.size()
/// faces. Empty vectors where the primitive has none.
MeshColour read_gltf_primitive_colour(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                      const std::vector<std::array<std::uint32_t, 3>>& faces,
                                      std::size_t vertex_count);

}  // namespace papernet::detail
