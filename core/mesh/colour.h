#pragma once
// The model's colour as loading found it (docs/colour.md): per face corner texture coordinates
// and colours, a material per face, the materials and their textures' encoded images.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace papernet {

using UV = std::array<double, 2>;    ///< glTF convention: u right, v down, origin top left
using RGBA = std::array<double, 4>;  ///< linear 0..1, as glTF's baseColorFactor and COLOR_0

/// How a texture is sampled (glTF sampler codes: 10497 repeat, 33071 clamp, 33648 mirror;
/// 9728 nearest, 9729 linear, 9984..9987 mipmap modes; 0 = unset).
struct TextureSampler {
  int wrap_s = 10497, wrap_t = 10497;
  int mag_filter = 0, min_filter = 0;
};

/// An image a material samples: the file's bytes as they came (PNG or JPEG), its size checked
/// by decoding it.
struct Texture {
  std::string name;
  std::string mime_type;  ///< "image/png" or "image/jpeg"
  int width = 0, height = 0;
  TextureSampler sampler;
  std::string bytes;
};

/// How a material's alpha (the base colour's, times its texture's) is read: glTF's alphaMode.
/// Opaque ignores it; Mask shows the surface where alpha is at least the cutoff and nothing
/// elsewhere; Blend lets what is behind show through. On paper, what does not show is the paper.
enum class AlphaMode { Opaque, Mask, Blend };

struct Material {
  std::string name;
  RGBA base_color{1, 1, 1, 1};  ///< glTF baseColorFactor, OBJ Kd (alpha d)
  int texture = -1;             ///< index into MeshColour::textures, -1 without one
  AlphaMode alpha_mode = AlphaMode::Opaque;
  double alpha_cutoff = 0.5;  ///< for AlphaMode::Mask
};

/// "OPAQUE", "MASK" or "BLEND", as glTF spells them.
const char* alpha_mode_name(AlphaMode mode);

/// Per-face colour data of a mesh, indexed like Mesh::faces. Each vector is empty when the
/// input has none; otherwise it has one entry per face. A face without texture coordinates
/// (or colours) in a mesh that has some for others holds NaN there.
struct MeshColour {
  std::vector<std::array<UV, 3>> uvs;        ///< per corner, in the face's corner order
  std::vector<std::array<RGBA, 3>> colours;  ///< per corner vertex colours (COLOR_0, PLY)
  std::vector<int> face_materials;           ///< index into materials, -1 for none
  std::vector<Material> materials;
  std::vector<Texture> textures;

  bool empty() const { return uvs.empty() && colours.empty() && face_materials.empty(); }
};

/// A corner that names no corner of the input: its data are NaN (uvs, colours).
constexpr int kNoCorner = -1;

/// `colour` for a mesh whose face i is made of input corners `corners[i]` (3 * face + corner,
/// or kNoCorner): per-corner data follow their corners, a face's material follows the face of
/// its first named corner. Materials and textures are kept.
MeshColour remap_corners(const MeshColour& colour, const std::vector<std::array<int, 3>>& corners);

/// `colour` for the faces `faces` of its mesh, in that order (corners unchanged).
MeshColour select_faces(const MeshColour& colour, const std::vector<int>& faces);

/// Appends the per-face data of `more` (a mesh of `more_faces` faces sharing `into`'s
/// materials) to `into` (a mesh of `into_faces` faces); where one side has data the other lacks,
/// the other is filled with NaN / -1 so that every vector stays one entry per face.
void append_faces(MeshColour& into, std::size_t into_faces, const MeshColour& more,
                  std::size_t more_faces);

}  // namespace papernet
