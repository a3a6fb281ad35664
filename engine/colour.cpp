// Colour for approximate pieces (docs/colour.md, "Printing"): a coarser mesh has faces of its
// own, without texture coordinates. Each such face is cut into small triangles, and each small
// triangle takes its colour from the input face nearest to its centre, as a bake from one
// surface to another does: its corners projected onto that face's plane, their barycentric
// coordinates there giving texture coordinates and vertex colours.
#include <algorithm>
#include <cmath>

#include "core/mesh/face_tree.h"
#include "engine/internal/steps.h"

namespace papernet::engine_detail {
namespace {

// Side of the small triangles a face is cut into, printed millimetres, and their most per side.
constexpr double kBakeStepMm = 2.5;
constexpr int kMaxBakeSteps = 24;

// Barycentric coordinates of p's projection onto the plane of triangle abc (outside it too).
std::array<double, 3> plane_barycentric(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 v0 = b - a, v1 = c - a, v2 = p - a;
  const double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1);
  const double d20 = dot(v2, v0), d21 = dot(v2, v1);
  const double denom = d00 * d11 - d01 * d01;
  if (!(std::abs(denom) > 1e-300)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  const double v = (d11 * d20 - d01 * d21) / denom, w = (d00 * d21 - d01 * d20) / denom;
  return {1 - v - w, v, w};
}

template <typename T>
T blend(const std::array<T, 3>& corner, const std::array<double, 3>& w) {
  T out{};
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = w[0] * corner[0][i] + w[1] * corner[1][i] + w[2] * corner[2][i];
  return out;
}

bool folds_into_part(const Piece& piece, const Mesh& part) {
  return piece.mesh.faces.size() == part.faces.size() && piece.mesh.vertices == part.vertices;
}

}  // namespace

std::vector<std::vector<ColourTriangle>> bake_colour(const std::vector<Piece>& pieces,
                                                     const Prepared& input, double scale) {
  std::size_t all = 0;
  for (const Piece& p : pieces) all += p.mesh.faces.size();
  std::vector<std::vector<ColourTriangle>> out(all);
  std::size_t base = 0;
  for (std::size_t p = 0; p < pieces.size(); base += pieces[p].mesh.faces.size(), ++p) {
    if (p >= input.part_colours.size() || input.part_colours[p].empty() ||
        folds_into_part(pieces[p], input.parts[p]))
      continue;
    const Mesh& part = input.parts[p];
    const MeshColour& colour = input.part_colours[p];
    const Mesh& mesh = pieces[p].mesh;
    const FaceTree tree(part);
    int hint = -1;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      const auto& t = mesh.faces[f];
      const Vec3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
      const double longest = std::max({norm(b - a), norm(c - b), norm(a - c)}) * scale;
      const int n =
          std::clamp(static_cast<int>(std::ceil(longest / kBakeStepMm)), 1, kMaxBakeSteps);
      auto corner = [&](int i, int j) {  // grid point i, j: barycentric (n - i - j, i, j) / n
        return std::array<double, 3>{double(n - i - j) / n, double(i) / n, double(j) / n};
      };
      auto point = [&](const std::array<double, 3>& w) { return w[0] * a + w[1] * b + w[2] * c; };
      auto add = [&](std::array<std::array<double, 3>, 3> at) {
        const Vec3 centre = (1.0 / 3) * (point(at[0]) + point(at[1]) + point(at[2]));
        const int g = tree.closest(centre, hint).second;
        if (g < 0) return;
        hint = g;
        const auto& s = part.faces[g];
        ColourTriangle tri;
        tri.at = at;
        tri.source = g;
        tri.material = static_cast<std::size_t>(g) < colour.face_materials.size()
                           ? colour.face_materials[g]
                           : -1;
        for (int k = 0; k < 3; ++k) {
          const auto w = plane_barycentric(point(at[k]), part.vertices[s[0]], part.vertices[s[1]],
                                           part.vertices[s[2]]);
          if (static_cast<std::size_t>(g) < colour.uvs.size()) tri.uv[k] = blend(colour.uvs[g], w);
          if (static_cast<std::size_t>(g) < colour.colours.size())
            tri.rgba[k] = blend(colour.colours[g], w);
        }
        out[base + f].push_back(tri);
      };
      for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j) {
          add({corner(i, j), corner(i + 1, j), corner(i, j + 1)});
          if (i + j + 1 < n) add({corner(i + 1, j), corner(i + 1, j + 1), corner(i, j + 1)});
        }
    }
  }
  return out;
}

}  // namespace papernet::engine_detail
