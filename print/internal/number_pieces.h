#pragma once
// Private to print/: how grown and merged pieces are numbered (print/fit.h, FitPieces).

#include <vector>

#include "print/fit.h"

namespace papernet::print_detail {

/// Sets `out.piece` to each face's piece, numbered by its first face (`of`: each face's piece
/// under any ids), `out.pieces` to their count and `out.cut_links` to the pieces beyond the
/// parts (values of `part`).
void number_pieces(std::vector<int> of, const std::vector<int>& part, FitPieces& out);

}  // namespace papernet::print_detail
