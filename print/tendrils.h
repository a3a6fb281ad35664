#pragma once

#include <vector>

#include "print/fit.h"

// Tendrils of sprawling pieces cut off where that saves a sheet (docs/print.md, "Tendrils cut off
// to save a sheet").

namespace papernet {

/// A link of an unfold tree cut by cut_tendrils: `face` made a root, where it hung from `parent`.
struct TendrilCut {
  int face = -1;
  int parent = -1;
};

/// Tendrils of sprawling pieces cut off (docs/print.md, "Tendrils cut off to save a sheet"):
/// `count` times, the unfold-tree link of `pieces` whose cut most shrinks the convex hull of its
/// piece (the piece's hull area less those of the two pieces the cut makes) is cut, a new piece
/// with its own 2D frame unchanged; fewer when no cut shrinks a hull. The pieces are numbered
/// anew by their trees (a piece for each root, in the roots' order by face). Returns the cuts
/// made, in order.
std::vector<TendrilCut> cut_tendrils(FitPieces& pieces, int count);

/// `cut` undone: its face hangs from its parent again, and the pieces are numbered anew.
void undo_tendril_cut(FitPieces& pieces, const TendrilCut& cut);

}  // namespace papernet
