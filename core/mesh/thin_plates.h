#pragma once

#include <optional>

#include "core/mesh/mesh.h"

namespace papernet {

/// One side of `mesh` taken as a plate. Its faces joined over folds of less than 60 degrees make
/// sheets (a flat plate has two, its top and its bottom, and the narrow walls around). A sheet
/// that holds between a third and 0.6 of `mesh`'s area is a side (a plate's holds about half;
/// the rest is its other side and its walls); of two sides, the one with fewer vertices inside it
/// that are not flat (each needs a cut to print) is returned, then the larger: a mesh of its own,
/// an open surface with the vertices it uses. Where the plate is thin (the caller measures how
/// far `mesh` is from the result: about the plate's thickness), that side is the plate printed
/// as one layer of card instead of a box whose walls are too narrow to fold, label or glue
/// (docs/print.md, "Detail"). None when no sheet is a side, or the side is not manifold at a
/// vertex (two fans of it meet there).
/// \throw InvalidInputException when `mesh` is not a manifold, oriented triangle mesh.
std::optional<Mesh> plate_side(const Mesh& mesh);

}  // namespace papernet
