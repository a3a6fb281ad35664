#pragma once

#include <vector>

#include "core/mesh/mesh.h"

namespace papernet {

/// Sum of the face angles at every vertex (0 for vertices in no face): 2 pi where the surface
/// around an inner vertex is flat; more than 2 pi at a border vertex where the surface laid flat
/// would fold over itself.
std::vector<double> angle_sums(const Mesh& mesh);

/// Angle defect of every vertex: 2 pi minus the sum of its face angles (its discrete Gaussian
/// curvature; 0 where the surface is flat, positive at a cone, negative at a saddle); 0 for
/// boundary vertices and vertices in no face. A cut edge ending at a vertex opens there by its
/// defect, which decides whether a glue tab fits at the end of a cut (core/tabs).
std::vector<double> angle_defects(const Mesh& mesh);

}  // namespace papernet
