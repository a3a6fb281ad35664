#pragma once

#include <cstddef>

#include "core/mesh/face_tree.h"
#include "core/mesh/mesh.h"

namespace papernet {

struct HausdorffOptions {
  /// Stop when the true distance is known to lie within [distance, distance·(1 + this)].
  double relative_accuracy = 0.01;
  /// Or within this fraction of the first mesh's diagonal, whichever is larger: two meshes on
  /// the same surface, triangulated differently, would otherwise need endless refinement.
  double absolute_accuracy = 1e-6;
  /// Work cap: triangles refined per direction (each costs three closest-point queries). When
  /// it is hit, `upper_bound` stays wider than the accuracy asked for (and says so).
  std::size_t max_refinements = 200'000;
};

/// Both bounds divided by the bounding-box diagonal of the first mesh.
struct HausdorffResult {
  double distance = 0;     ///< attained: some surface point is this far from the other surface
  double upper_bound = 0;  ///< no surface point is farther than this from the other surface
};

/// Two-sided Hausdorff distance between the surfaces of `a` and `b` (max over both directions of
/// the largest point-to-surface distance), relative to `a`'s bounding-box diagonal.
///
/// Accuracy: exact point-to-triangle distances through a bounding-volume hierarchy, and a
/// branch-and-bound over the faces, subdivided 1:4 where needed. The distance to a surface is
/// 1-Lipschitz, so over a triangle it exceeds the largest value at its corners by at most its
/// longest edge / sqrt(3) (the farthest a point of a triangle can be from all its corners); and
/// the distance to one fixed triangle is convex, so its maximum over a triangle sits at a corner.
/// The smaller of these two bounds is kept per triangle; refinement stops when no triangle's
/// bound exceeds the best attained distance by more than the requested accuracy.
/// \throw InvalidInputException when either mesh has no faces.
HausdorffResult hausdorff_distance(const Mesh& a, const Mesh& b,
                                   const HausdorffOptions& options = {});

/// Two-sided Hausdorff distance of `approximation` to `input`, relative to the input's
/// bounding-box diagonal, with the bounded refinement that approximate results use (its time on
/// real models, CAD plates fanned into long slivers among them: docs/performance.md).
double approximation_distance(const Mesh& input, const Mesh& approximation);

/// True when approximation_distance(input, approximation) <= `distance` (relative to the input's
/// diagonal, as it), found with less work: it stops at the first point farther than `distance`,
/// and refines no part of a surface known to be within it.
bool approximation_within(const Mesh& input, const Mesh& approximation, double distance);

/// approximation_distance and approximation_within of many approximations of one input, its
/// face tree built once. Keeps a reference to `input`, which must outlive it.
class ApproximationMeasure {
 public:
  explicit ApproximationMeasure(const Mesh& input);
  /// approximation_distance(input, approximation).
  double distance(const Mesh& approximation) const;
  /// approximation_within(input, approximation, distance).
  bool within(const Mesh& approximation, double distance) const;

 private:
  const Mesh& input_;
  FaceTree tree_;
  double diagonal_;
};

}  // namespace papernet
