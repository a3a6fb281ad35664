// Colour for approximate pieces (docs/colour.md, "Printing"): a coarser mesh has faces of its
// own, without texture coordinates. Each such face is cut into small triangles, and each small
// triangle takes its colour from the input face nearest to its centre, as a bake from one
// surface to another does: its corners projected onto that face's plane, their barycentric
// coordinates there giving texture coordinates and vertex colours.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <optional>

#include "core/io/image.h"
#include "core/mesh/face_tree.h"
#include "engine/internal/colour.h"

namespace papernet::engine_detail {
namespace {

// The most small triangles a face is cut into a side (of kBakeStepMm or more).
constexpr int kMaxBakeSteps = 24;

// Steps a side of a face whose longest edge prints `longest` mm, for small triangles of side
// `step` mm: n x n small triangles.
int bake_steps(double longest, double step) {
  const double n = std::ceil(longest / step);
  return std::isfinite(n) ? static_cast<int>(std::clamp(n, 1.0, double(kMaxBakeSteps))) : 1;
}

// The side of the small triangles, at least kBakeStepMm, for which the faces whose longest edges
// print `longest` mm are cut into at most `most` of them (each face at least one): the smallest
// found by bisection to a hundredth of a millimetre.
double bake_step(const std::vector<double>& longest, std::size_t most) {
  const auto count = [&](double step) {
    std::size_t n = 0;
    for (const double l : longest) {
      const auto k = static_cast<std::size_t>(bake_steps(l, step));
      n += k * k;
    }
    return n;
  };
  if (count(kBakeStepMm) <= most) return kBakeStepMm;
  double lo = kBakeStepMm, hi = kBakeStepMm;
  for (const double l : longest) hi = std::max(hi, l);  // one triangle a face
  while (hi - lo > 0.01) (count(0.5 * (lo + hi)) <= most ? hi : lo) = 0.5 * (lo + hi);
  return hi;
}

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

// A texel of `image` at texture coordinates `uv` (glTF: v down), its nearest pixel, wrapped as
// `sampler` says; linear RGBA.
RGBA texel(const Image& image, const TextureSampler& sampler, UV uv) {
  const auto wrap = [](double t, int mode) {
    if (mode == 33071) return std::clamp(t, 0.0, 1.0);  // clamp
    const double f = t - std::floor(t);
    if (mode == 33648 && static_cast<long long>(std::floor(t)) % 2 != 0) return 1 - f;  // mirror
    return f;
  };
  const auto linear = [](double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  const double u = wrap(uv[0], sampler.wrap_s), v = wrap(uv[1], sampler.wrap_t);
  const int x = std::clamp(static_cast<int>(u * image.width), 0, image.width - 1);
  const int y = std::clamp(static_cast<int>(v * image.height), 0, image.height - 1);
  const std::uint8_t* p = &image.rgba[(static_cast<std::size_t>(y) * image.width + x) * 4];
  return {linear(p[0] / 255.0), linear(p[1] / 255.0), linear(p[2] / 255.0), p[3] / 255.0};
}

}  // namespace

std::vector<std::optional<Image>> decode_textures(const MeshColour& library) {
  std::vector<std::optional<Image>> images(library.textures.size());
  for (std::size_t t = 0; t < images.size(); ++t) {
    try {
      images[t] = decode_image(library.textures[t].bytes);
      if (images[t]->width <= 0 || images[t]->height <= 0) images[t].reset();
    } catch (const std::exception&) {
      images[t].reset();
    }
  }
  return images;
}

MeshColour corner_colours(const Mesh& mesh, const Mesh& part, const MeshColour& colour,
                          const MeshColour& library,
                          const std::vector<std::optional<Image>>& images) {
  MeshColour out;
  out.materials = library.materials;
  out.textures = library.textures;
  out.face_materials.assign(mesh.faces.size(), -1);
  out.colours.assign(mesh.faces.size(), {});
  // Texture coordinates where the part has them: none (null) on the coarser faces.
  if (!colour.uvs.empty())
    out.uvs.assign(mesh.faces.size(), {UV{ColourTriangle::kNone, ColourTriangle::kNone},
                                       UV{ColourTriangle::kNone, ColourTriangle::kNone},
                                       UV{ColourTriangle::kNone, ColourTriangle::kNone}});
  const FaceTree tree(part);
  int hint = -1;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = mesh.vertices[mesh.faces[f][k]];
      RGBA rgba{1, 1, 1, 1};
      const int g = tree.closest(p, hint).second;
      if (g >= 0) {
        hint = g;
        const auto& s = part.faces[g];
        // The nearest point of face g: p on its plane, its weights clamped to the face.
        auto w =
            plane_barycentric(p, part.vertices[s[0]], part.vertices[s[1]], part.vertices[s[2]]);
        double sum = 0;
        for (double& x : w) sum += (x = std::max(x, 0.0));
        for (double& x : w) x = sum > 0 ? x / sum : 1.0 / 3;
        const int m = static_cast<std::size_t>(g) < colour.face_materials.size()
                          ? colour.face_materials[g]
                          : -1;
        if (m >= 0 && static_cast<std::size_t>(m) < library.materials.size()) {
          const Material& material = library.materials[m];
          rgba = material.base_color;
          const int t = material.texture;
          if (t >= 0 && static_cast<std::size_t>(t) < images.size() && images[t] &&
              static_cast<std::size_t>(g) < colour.uvs.size()) {
            const UV uv = blend(colour.uvs[g], w);
            if (std::isfinite(uv[0]) && std::isfinite(uv[1])) {
              const RGBA c = texel(*images[t], library.textures[t].sampler, uv);
              for (int i = 0; i < 4; ++i) rgba[i] *= c[i];
            }
          }
        }
        if (static_cast<std::size_t>(g) < colour.colours.size()) {
          const RGBA c = blend(colour.colours[g], w);
          for (int i = 0; i < 4; ++i)
            if (std::isfinite(c[i])) rgba[i] *= c[i];
        }
      }
      out.colours[f][k] = rgba;
    }
  return out;
}

BakedColour bake_colour(const std::vector<Piece>& pieces, const Prepared& input, double scale,
                        std::size_t most_triangles) {
  const auto baked = [&](std::size_t p) {
    return p < input.part_colours.size() && !input.part_colours[p].empty() &&
           !folds_into_part(pieces[p], input.parts[p]);
  };
  const auto longest_mm = [&](const Mesh& mesh, const std::array<int, 3>& t) {
    const Vec3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    return std::max({norm(b - a), norm(c - b), norm(a - c)}) * scale;
  };
  std::size_t all = 0;
  std::vector<double> longest;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    all += pieces[p].mesh.faces.size();
    if (baked(p))
      for (const auto& t : pieces[p].mesh.faces) longest.push_back(longest_mm(pieces[p].mesh, t));
  }
  BakedColour out_colour;
  out_colour.step_mm = bake_step(longest, most_triangles);
  out_colour.coarser = out_colour.step_mm > kBakeStepMm;
  auto& out = out_colour.faces;
  out.resize(all);
  std::size_t base = 0;
  for (std::size_t p = 0; p < pieces.size(); base += pieces[p].mesh.faces.size(), ++p) {
    if (!baked(p)) continue;
    const Mesh& part = input.parts[p];
    const MeshColour& colour = input.part_colours[p];
    const Mesh& mesh = pieces[p].mesh;
    const FaceTree tree(part);
    int hint = -1;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      const auto& t = mesh.faces[f];
      const Vec3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
      const int n = bake_steps(longest_mm(mesh, t), out_colour.step_mm);
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
  return out_colour;
}

}  // namespace papernet::engine_detail
