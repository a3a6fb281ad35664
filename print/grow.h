#pragma once

#include <cstddef>
#include <vector>

#include "core/unfold/net.h"
#include "print/fit.h"

// Pieces grown from single faces, the fit layout's other way of making pieces (docs/print.md,
// "Fit layout").

namespace papernet {

/// Pieces grown from single faces instead of cut from a net (docs/print.md, "Fit layout"), as
/// Blender's paper-model exporter grows its islands: every face of `mesh` starts as a piece of
/// its own, laid flat; then the mesh's edges, flattest fold first (concave folds count double,
/// longer edges first among equal folds), each join the two pieces on its sides when the joined
/// piece lies flat without overlap (kOverlapTolerance of the mesh's diagonal) and, at `scale`
/// millimetres per unit, fits `room` as cut_to_fit's pieces do. The pieces are compact where a
/// net's subtrees sprawl. No piece takes faces of two parts (values of `piece`); `cut_links`
/// counts the pieces beyond the parts. Every face must fit `room.room`, or `room.alone` as a piece
/// of its own (listed in `large`; cut_to_fit throws otherwise).
/// With `tab_height` > 0 (model units) a join is also refused when it leaves a cut edge inside
/// the joined piece (a slit: an edge whose two faces were in the two pieces, not glued) where a
/// tab that high (of core/tabs' tab_shapes(`tab_angle_deg`), half the edge on a short one) fits
/// on neither side without overlapping a face of the piece, unless its two sides lie on each
/// other: more, smaller pieces, and tabs instead of glue strips on those cuts. Deterministic:
/// the same mesh grows the same pieces.
/// With `regrow_faces` > 0, the pieces of at most that many faces left when no join is left
/// (small pieces between larger ones, which no join of a whole piece fitted) are taken apart
/// again, and their faces, one at a time, join the pieces around them first, then each other;
/// the result is kept when it has fewer pieces.
FitPieces grow_to_fit(const Mesh& mesh, const std::vector<int>& piece, double scale, FitRoom room,
                      double tab_height = 0, double tab_angle_deg = 45,
                      std::size_t regrow_faces = 0);

}  // namespace papernet
