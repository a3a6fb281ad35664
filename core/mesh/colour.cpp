// Per-face colour data following faces and corners through the steps that renumber them.
#include "core/mesh/colour.h"

#include <limits>

namespace papernet {

const char* alpha_mode_name(AlphaMode mode) {
  switch (mode) {
    case AlphaMode::Mask:
      return "MASK";
    case AlphaMode::Blend:
      return "BLEND";
    case AlphaMode::Opaque:
      break;
  }
  return "OPAQUE";
}
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr UV kNoUV{kNaN, kNaN};
constexpr RGBA kNoRGBA{kNaN, kNaN, kNaN, kNaN};

template <typename T, typename Value>
void pad(std::vector<T>& v, std::size_t n, const Value& value) {
  if (v.size() < n) v.resize(n, value);
}

}  // namespace

MeshColour remap_corners(const MeshColour& colour, const std::vector<std::array<int, 3>>& corners) {
  MeshColour out;
  out.materials = colour.materials;
  out.textures = colour.textures;
  const std::size_t n = corners.size();
  if (!colour.uvs.empty()) out.uvs.assign(n, {kNoUV, kNoUV, kNoUV});
  if (!colour.colours.empty()) out.colours.assign(n, {kNoRGBA, kNoRGBA, kNoRGBA});
  if (!colour.face_materials.empty()) out.face_materials.assign(n, -1);
  for (std::size_t f = 0; f < n; ++f) {
    bool material = false;
    for (int k = 0; k < 3; ++k) {
      const int c = corners[f][k];
      if (c < 0) continue;
      const std::size_t face = std::size_t(c) / 3, corner = std::size_t(c) % 3;
      if (face < colour.uvs.size()) out.uvs[f][k] = colour.uvs[face][corner];
      if (face < colour.colours.size()) out.colours[f][k] = colour.colours[face][corner];
      if (!material && face < colour.face_materials.size()) {
        out.face_materials[f] = colour.face_materials[face];
        material = true;
      }
    }
  }
  return out;
}

MeshColour select_faces(const MeshColour& colour, const std::vector<int>& faces) {
  std::vector<std::array<int, 3>> corners(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i)
    corners[i] = {3 * faces[i], 3 * faces[i] + 1, 3 * faces[i] + 2};
  return remap_corners(colour, corners);
}

void append_faces(MeshColour& into, std::size_t into_faces, const MeshColour& more,
                  std::size_t more_faces) {
  const std::size_t n = into_faces + more_faces;
  const auto join = [&](auto& a, const auto& b, const auto& none) {
    if (a.empty() && b.empty()) return;
    pad(a, into_faces, none);
    a.resize(into_faces);
    a.insert(a.end(), b.begin(), b.begin() + std::min(b.size(), more_faces));
    pad(a, n, none);
  };
  join(into.uvs, more.uvs, std::array<UV, 3>{kNoUV, kNoUV, kNoUV});
  join(into.colours, more.colours, std::array<RGBA, 3>{kNoRGBA, kNoRGBA, kNoRGBA});
  join(into.face_materials, more.face_materials, -1);
}

}  // namespace papernet
