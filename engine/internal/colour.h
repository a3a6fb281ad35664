// Private to engine/: the colour of the pieces that fold into a coarser mesh than the input's
// (engine/colour.cpp): baked into small triangles for the print, and at the corners for the net
// document.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "core/io/image.h"
#include "core/mesh/colour.h"
#include "core/mesh/mesh.h"
#include "engine/internal/steps.h"

namespace papernet::engine_detail {

/// The side of the small triangles of bake_colour, printed millimetres, unless their number is
/// bounded lower.
inline constexpr double kBakeStepMm = 2.5;

/// The colour of the approximate pieces' faces, cut into small triangles (bake_colour).
struct BakedColour {
  /// Per face of the pieces side by side (as `assemble` puts them); empty for faces of pieces
  /// that fold into their part's own faces and for parts without colour.
  std::vector<std::vector<ColourTriangle>> faces;
  double step_mm = 0;    ///< the small triangles' side, printed millimetres
  bool coarser = false;  ///< larger than the usual side, to keep within the most triangles
};

/// The colour of each face of the approximate pieces, from the input surface nearest to it
/// (engine/colour.cpp). `scale` is the print's millimetres per model unit. The print draws each
/// small triangle on its own, so `most_triangles` bounds their number: the side grows until they
/// are that few (each face at least one).
BakedColour bake_colour(const std::vector<Piece>& pieces, const Prepared& input, double scale,
                        std::size_t most_triangles);

/// The colour of an approximate piece's `mesh` in the net document (engine/colour.cpp): each
/// corner's vertex colour is the input's colour at the point of `part` nearest to it (the
/// material's base colour, times its texture's nearest texel there, times the input's vertex
/// colour), no material and no texture coordinates. So a viewer of the folded net (the web
/// demo, a storefront's own) shows the model's colours on the coarser faces; the print bakes
/// them finer.
/// `colour` is the part's per-face data, `library` the input's materials and textures, `images`
/// those textures decoded (decode_textures).
MeshColour corner_colours(const Mesh& mesh, const Mesh& part, const MeshColour& colour,
                          const MeshColour& library,
                          const std::vector<std::optional<Image>>& images);

/// The textures of `library`, decoded; one that does not decode is empty (it samples as white;
/// the print says so).
std::vector<std::optional<Image>> decode_textures(const MeshColour& library);

}  // namespace papernet::engine_detail
