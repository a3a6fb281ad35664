#pragma once

#include <vector>

#include "core/unfold/net.h"

namespace papernet {

/// A net of several pieces, each in its own 2D frame, as one drawing: each piece turned so that
/// its minimum-area box lies flat (long side along x) and set beside the others in rows, largest
/// first, `gap` (model units) apart, the rows about as wide as the whole is high times the
/// sheet's proportion. Only rigid motions: every piece keeps its shape. One piece: `net` as it
/// is. (Nesting pieces onto the fewest sheets is the print's layout's job, not this.)
Net arrange_pieces(const Net& net, const std::vector<int>& piece, double gap);

}  // namespace papernet
