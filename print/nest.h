#pragma once

#include <vector>

#include "print/layout.h"
#include "print/pages.h"

namespace papernet {

/// Nests the pieces of a laid-out net onto the fewest sheets (docs/print.md, "Fit layout"): each
/// piece with its glue tabs, and each glue strip, is an outline (their union grown by half of
/// `spacing_mm`, so pieces keep that much paper between them to cut along), turned to lie along
/// its minimum-area box, then placed by print/internal/nest_outlines.h: largest first, on the
/// first sheet where one of its quarter turns fits, at the lowest free place of a grid of cells
/// (into other pieces' hollows too; cells of 0.5 mm, larger on a sheet longer than 450 mm, whose
/// grid has as many cells as one that long). Pieces must already fit a page's printable area
/// with their tabs (cut_to_fit).
///
/// `piece` gives each face's piece. Moves everything in `layout` (faces, tabs, strips, lines,
/// labels) rigidly to its sheet: sheet k is the window [k * (w + gap), (k + 1) * w + k * gap] x
/// [0, h] of the layout, w x h the printable area, and the PageLayout returned has one page per
/// sheet, `fitted` set, in the order of the lowest piece number each holds (pieces numbered in
/// build order: print/build_order.h; sheets of glue strips only last). Labels are turned to read
/// upright after the move.
/// \throw InvalidOptionException ("face_too_large", "size_mm") when a piece does not fit a page.
PageLayout nest_pages(PrintLayout& layout, const std::vector<int>& piece,
                      const PageOptions& options, double spacing_mm);

}  // namespace papernet
