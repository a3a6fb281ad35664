#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/io/load.h"
#include "core/mesh/mesh.h"

namespace papernet {

/// One thing found wrong with (or done to) a mesh. `code` is stable and machine-readable;
/// `message` says what and where in words a user can act on.
struct MeshProblem {
  std::string
      code;  ///< empty_mesh, non_finite_coordinates, degenerate_faces,
             ///< non_manifold_edges, non_manifold_vertices, inconsistent_orientation,
             ///< several_components (blocking); triangulated, kept_largest_component (notes)
  std::string message;
  bool blocking = true;       ///< false for notes that do not stop unfolding
  std::vector<int> elements;  ///< the first few faces/vertices/edges' vertices concerned
};

struct ValidateOptions {
  /// When the mesh has several components, judge (and return in `largest_component`) the one
  /// with the most faces instead of refusing.
  bool keep_largest_component = false;
  /// A face is degenerate when a vertex repeats or its area is at most this fraction of its
  /// longest edge squared (its corners are collinear up to rounding). Relative to the face, not
  /// the model, so that small but well-shaped faces of a large model are not flagged.
  double degenerate_area = 1e-12;
  std::size_t max_listed = 5;  ///< how many elements a message names
};

/// What validation found. Counts describe the judged mesh (the largest component when one was
/// kept). genus and boundary_loops are sums over components, from V - E + F = 2 - 2g - b.
struct ValidationReport {
  std::size_t vertices = 0, faces = 0, edges = 0, components = 0;
  std::size_t boundary_edges = 0, boundary_loops = 0;
  long genus = 0;
  std::vector<MeshProblem> problems;
  Mesh largest_component;  ///< filled only when keep_largest_component selected one

  /// True when no blocking problem was found: the mesh can be unfolded as it is.
  bool unfoldable() const;
  /// The first blocking problem's message, or "" when unfoldable.
  std::string reason() const;
};

/// A mesh that cannot be unfolded as it is, with everything validation found.
class InvalidMeshException : public InvalidInputException {
 public:
  explicit InvalidMeshException(ValidationReport report)
      : InvalidInputException(report.reason()), report_(std::move(report)) {}
  const ValidationReport& report() const { return report_; }

 private:
  ValidationReport report_;
};

/// Judges a triangle mesh: emptiness, finite coordinates, degenerate faces, manifold edges and
/// vertices, consistent orientation, connected components; counts genus and boundary loops.
/// Components are faces joined through shared vertices. Every problem is listed (not only the
/// first); faces with a repeated vertex are reported as degenerate and left out of the rest.
/// \pre every face index names an existing vertex (load_mesh guarantees it).
ValidationReport validate(const Mesh& mesh, const ValidateOptions& options = {});

/// As above, and notes what loading did (polygons triangulated).
ValidationReport validate(const LoadedMesh& loaded, const ValidateOptions& options = {});

}  // namespace papernet
