#pragma once

#include <span>
#include <vector>

#include "core/io/load.h"
#include "core/mesh/mesh.h"
#include "print/colour.h"

namespace papernet {

/// The directions to look at a model from, in its own coordinates.
struct ViewAxes {
  Vec3 up{0, 1, 0};     ///< up on the page
  Vec3 front{0, 0, 1};  ///< the side the model faces
};

/// The axes of a model read from `format`: Z up and -Y to the front for STL (the 3D printers'
/// convention), Y up and +Z to the front for the others (glTF's, and most scans' and OBJ's).
ViewAxes view_axes(MeshFormat format);

/// The model as built, drawn for the overview page (docs/print.md, "The overview page"): its
/// faces flat-shaded, each piece in a light colour of its own, the cuts between pieces drawn as
/// lines, and each piece's number where enough of the piece shows.
struct ModelView {
  PageImage image;  ///< the shaded model, at the box asked
  struct Number {
    int piece = -1;
    Vec2 at;          ///< centre of the text, page mm (y down)
    double size = 0;  ///< text height, mm
    /// A line from `from` (on the text's box) to `to` (where the piece shows most) for a number
    /// beside the model; the two equal `at` for a number on its piece.
    Vec2 from, to;
  };
  std::vector<Number> numbers;
};

/// The text heights a piece's number takes on a view, largest first (mm).
inline constexpr double kViewNumberMm[] = {3, 2.5, 2};

/// `mesh` with each face's piece `piece` (numbered in build order, from 0), seen from the
/// direction `toward` points to (orthographic, `up` up on the page), as large as fits the page box
/// [lo, hi] (mm, y down), its image at `dpi`; without `colour`, every piece light grey. A number's
/// box lies on its piece where it shows, apart from the other numbers; a piece showing too
/// little for one at 2 mm gets one beside the model, off it, with a line to the piece; a piece
/// that shows less than a square millimetre gets none.
ModelView draw_model_view(const Mesh& mesh, std::span<const int> piece, Vec3 toward, Vec3 up,
                          Vec2 lo, Vec2 hi, double dpi, bool colour = true);

}  // namespace papernet
