#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"

namespace papernet {

/// One kind of repair made to a mesh. `code` is stable and machine-readable:
/// removed_degenerate_faces, removed_duplicate_faces, cut_non_manifold_edges,
/// split_pinched_vertices, reoriented_faces, cut_non_orientable_edges.
struct MeshRepair {
  std::string code;
  std::size_t count = 0;
  std::string message;        ///< what and where, in words a user can act on
  std::vector<int> elements;  ///< the first few faces or vertices concerned (input numbering)
};

struct RepairOptions {
  /// A face is degenerate when a vertex repeats or its area is at most this fraction of its
  /// longest edge squared (as ValidateOptions::degenerate_area).
  double degenerate_area = 1e-12;
  std::size_t max_listed = 5;  ///< how many elements a message names
};

struct RepairResult {
  Mesh mesh;  ///< manifold, consistently oriented, without degenerate or duplicate faces
  std::vector<MeshRepair> repairs;  ///< one entry per kind of repair made, none when none was
  /// For each face of `mesh`, the input corner (3 * input face + k) each of its corners comes
  /// from: what carries texture coordinates and colours through repair (remap_corners in
  /// core/mesh/colour.h). A face turned to agree with its neighbours has its corners turned too.
  std::vector<std::array<int, 3>> corners;
};

/// Repairs what can be repaired without changing the shape (docs/inputs.md):
/// - faces with a repeated vertex and duplicate faces are removed;
/// - zero-area faces are removed without opening the surface: a cap (a vertex on the opposite
///   edge) by flipping that edge with its neighbour, a needle (two vertices almost together) by
///   collapsing its shortest edge; where neither is possible, the face is dropped;
/// - edges shared by more than two faces are cut (faces beyond a glued pair keep their own side),
///   and vertices whose faces form several fans (pinches) are split, one vertex per fan (a cut
///   is always allowed in an unfolding);
/// - each connected part is oriented consistently (outward when it is closed), cutting the
///   edges of a part that cannot be (a Moebius strip).
/// `raw_corners` (LoadedMesh::raw_faces) names the vertex each corner had before the loader
/// merged vertices at equal positions; where the loader's merge alone made an edge non-manifold
/// or a vertex pinched (separate surfaces touching), undoing it is no repair and is not reported.
/// Empty: every corner's own vertex. Vertices used by no face are dropped.
/// \pre every face index names an existing vertex; coordinates are finite.
RepairResult repair_mesh(const Mesh& mesh, const std::vector<std::array<int, 3>>& raw_corners = {},
                         const RepairOptions& options = {});

/// The connected parts of `mesh` (faces joined by shared vertices), largest first (ties in face
/// order), each with vertices of its own. `faces_of`, when given, receives each part's faces
/// (indices into `mesh.faces`, in the part's face order).
std::vector<Mesh> split_components(const Mesh& mesh,
                                   std::vector<std::vector<int>>* faces_of = nullptr);

}  // namespace papernet
