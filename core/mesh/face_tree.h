#pragma once
// Closest faces of a mesh to points in space: a bounding-volume hierarchy over its faces (for
// the Hausdorff distance, and for colouring a coarser mesh from the surface it approximates).

#include <utility>
#include <vector>

#include "core/mesh/mesh.h"

namespace papernet {

/// Squared distance from p to triangle abc.
double distance2_to_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c);

/// Bounding-volume hierarchy over a mesh's faces for closest-point queries. Keeps a reference
/// to the mesh, which must outlive it.
class FaceTree {
 public:
  explicit FaceTree(const Mesh& mesh);

  /// Squared distance from p to face `face`.
  double distance2(Vec3 p, int face) const;

  /// Closest face to p and its squared distance; `hint` (a face likely near p, or -1) primes
  /// the search bound. With `enough2` > 0 the search ends at the first face found within that
  /// squared distance, which need not be the closest: a caller that only needs to know whether
  /// p is within it (or p's distance where it is larger) saves the rest of the search.
  std::pair<double, int> closest(Vec3 p, int hint = -1, double enough2 = 0) const;

 private:
  static constexpr int kLeaf = 4;
  struct Node {
    Vec3 lo, hi;
    int first = 0, count = 0;  // leaf: faces order_[first, first + count)
    int right = -1;            // inner node (count == 0): children `first` and `right`
  };

  static double box_distance2(Vec3 p, const Node& n);
  int build(int begin, int end);

  const Mesh& mesh_;
  std::vector<int> order_;
  std::vector<Vec3> centroid_;
  std::vector<Node> nodes_;
};

}  // namespace papernet
