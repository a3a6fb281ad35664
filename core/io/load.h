#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/image.h"
#include "core/mesh/colour.h"
#include "core/mesh/mesh.h"

namespace papernet {

enum class MeshFormat { Unknown, Obj, Off, Ply, Stl, Gltf, Glb, Draco };

/// Name of a format as users write it ("obj", "glb", ...).
std::string format_name(MeshFormat format);

/// Format from a file name's extension (case-insensitive); Unknown when there is none we read.
MeshFormat format_from_extension(std::string_view path);

/// Format from the content: glTF/Draco magic, JSON, "ply", "OFF", binary STL (size matches its
/// triangle count), "solid", OBJ keywords. Unknown when none fits.
MeshFormat sniff_format(std::string_view bytes);

/// Limits and inputs for loading. Limits are checked before large allocations.
struct LoadOptions {
  std::size_t max_bytes = std::size_t{256} << 20;  ///< size of the mesh file itself
  std::size_t max_faces = 2'000'000;               ///< faces after triangulation
  std::size_t max_vertices = 6'000'000;            ///< positions read, before welding
  /// Pixels of one texture image, checked from its header before it is decoded.
  std::uint64_t max_image_pixels = kDefaultMaxImagePixels;
  /// Files that came with a .gltf (its external buffers and images) or an OBJ (its MTL files
  /// and their images), by the relative name the model uses.
  /// A .gltf never reads anything from disk by itself: a URI not found here is an error.
  std::map<std::string, std::string> external_files;
};

/// What was loaded, and what loading had to do to it.
struct LoadedMesh {
  Mesh mesh;  ///< welded: vertices with equal positions merged
  MeshFormat format = MeshFormat::Unknown;
  std::size_t raw_vertices = 0;  ///< vertex count before welding
  /// The vertex each corner had before welding (faces as mesh.faces): what repair_mesh needs
  /// to tell the file's own connections from those welding made.
  std::vector<std::array<int, 3>> raw_faces;
  bool triangulated = false;       ///< polygons (or strips/fans) were split into triangles
  std::vector<std::string> notes;  ///< what else loading did (skipped lines, points, primitives)
  /// Texture coordinates, vertex colours and materials per face, as mesh.faces; welding merges
  /// positions only, so each corner keeps its own (docs/colour.md).
  MeshColour colour;
};

/// Loads a mesh from bytes in memory. `format` may be Unknown: it is then sniffed from content.
/// Polygons are fanned into triangles; vertices used by no face are dropped; lines and points
/// are skipped (and noted); a file with nothing triangular left loads as an empty mesh unless the
/// only content was a refused kind (glTF line/point primitives, Draco point clouds).
/// \throw IOException naming the fault (unreadable, unsupported, truncated, over a limit).
LoadedMesh load_mesh(std::string_view bytes, MeshFormat format, const LoadOptions& options = {});

/// URIs of the external buffers and images a .gltf names (URL-decoded, data URIs left out): the
/// keys the loader will look up in `LoadOptions::external_files`. The caller decides which to
/// supply (the command-line tool only relative names inside the file's folder, never ".."). \throw
/// IOException when the text is not glTF JSON.
std::vector<std::string> gltf_external_uris(std::string_view gltf_json);

/// The bytes of a file, refused when it has more than `max_bytes`.
/// \throw IOException naming the fault (LimitExceededException over the limit).
std::string read_mesh_file(const std::string& path, std::size_t max_bytes);

/// Loads a mesh file; the format comes from the extension, else from the content. For .gltf,
/// sibling files named by the glTF are read only when they are listed in `options.external_files`;
/// the command-line tool fills that map from the folder. \throw IOException naming the fault.
LoadedMesh load_mesh_file(const std::string& path, const LoadOptions& options = {});

}  // namespace papernet
