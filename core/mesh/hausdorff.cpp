#include "core/mesh/hausdorff.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/mesh/face_tree.h"

namespace papernet {
namespace {

struct Patch {
  std::array<Vec3, 3> p;
  std::array<double, 3> d;  // distance of each corner to the other surface
  std::array<int, 3> near;  // the face of the other surface closest to each corner
  double upper = 0;         // no point of the patch is farther than this from the other surface
  bool operator<(const Patch& o) const { return upper < o.upper; }
};

void bound(Patch& patch, const FaceTree& tree) {
  const double longest =
      std::sqrt(std::max({dot(patch.p[1] - patch.p[0], patch.p[1] - patch.p[0]),
                          dot(patch.p[2] - patch.p[1], patch.p[2] - patch.p[1]),
                          dot(patch.p[0] - patch.p[2], patch.p[0] - patch.p[2])}));
  double upper = std::max({patch.d[0], patch.d[1], patch.d[2]}) + longest / std::sqrt(3.0);
  for (int j = 0; j < 3; ++j) {
    double worst = 0;
    for (int i = 0; i < 3 && worst < upper; ++i)
      worst = std::max(worst,
                       i == j ? patch.d[i] : std::sqrt(tree.distance2(patch.p[i], patch.near[j])));
    upper = std::min(upper, worst);
  }
  patch.upper = upper;
}

// One direction, from the surface of `from` to the one in `tree`. Raises `attained` to the
// largest distance reached by a sampled point; returns an upper bound of the direction. With a
// finite `enough`, it stops as soon as `attained` passes it, and refines no patch whose bound is
// within it.
double one_side(const Mesh& from, const FaceTree& tree, double& attained, double rel, double abs,
                std::size_t max_refinements, double enough) {
  // A point within half the distance attained so far of the other surface cannot raise it, so
  // its search may end at the first face within that half (FaceTree::closest's `enough2`):
  // `attained` stays exact, and the bounds below, from a distance no smaller than the true one,
  // stay bounds, exact for the points that come near the largest distance, whose triangles are
  // refined first (docs/performance.md). On CAD plates fanned into long slivers, where one exact
  // search measures hundreds of faces, most searches end so.
  std::vector<double> vd(from.vertices.size(), -1);
  std::vector<int> vn(from.vertices.size(), -1);
  int hint = -1;
  for (const auto& f : from.faces)
    for (int v : f) {
      if (vd[v] >= 0) continue;
      const auto [d2, face] = tree.closest(from.vertices[v], hint, 0.25 * attained * attained);
      vd[v] = std::sqrt(d2);
      vn[v] = hint = face;
      attained = std::max(attained, vd[v]);
      if (attained > enough) return attained;
    }
  const double settled = std::isfinite(enough) ? enough : 0;  // no patch within this is refined
  auto done = [&](double upper) {
    return upper <= std::max({attained * (1 + rel), attained + abs, settled});
  };
  std::priority_queue<Patch> heap;
  for (const auto& f : from.faces) {
    Patch patch;
    for (int i = 0; i < 3; ++i) {
      patch.p[i] = from.vertices[f[i]];
      patch.d[i] = vd[f[i]];
      patch.near[i] = vn[f[i]];
    }
    bound(patch, tree);
    if (!done(patch.upper)) heap.push(patch);
  }
  std::size_t refined = 0;
  while (!heap.empty()) {
    const Patch top = heap.top();
    if (done(top.upper) || refined >= max_refinements) return std::max(top.upper, attained);
    if (attained > enough) return attained;
    heap.pop();
    ++refined;
    std::array<Vec3, 3> m;
    std::array<double, 3> md;
    std::array<int, 3> mn;
    for (int i = 0; i < 3; ++i) {
      m[i] = 0.5 * (top.p[i] + top.p[(i + 1) % 3]);
      const auto [d2, face] = tree.closest(m[i], top.near[i], 0.25 * attained * attained);
      md[i] = std::sqrt(d2);
      mn[i] = face;
      attained = std::max(attained, md[i]);
    }
    // Corners then edge midpoints (m[i] between corners i and i+1): four children.
    const Patch children[4] = {
        {{top.p[0], m[0], m[2]}, {top.d[0], md[0], md[2]}, {top.near[0], mn[0], mn[2]}, 0},
        {{m[0], top.p[1], m[1]}, {md[0], top.d[1], md[1]}, {mn[0], top.near[1], mn[1]}, 0},
        {{m[2], m[1], top.p[2]}, {md[2], md[1], top.d[2]}, {mn[2], mn[1], top.near[2]}, 0},
        {{m[0], m[1], m[2]}, {md[0], md[1], md[2]}, {mn[0], mn[1], mn[2]}, 0}};
    for (Patch child : children) {
      bound(child, tree);
      if (!done(child.upper)) heap.push(child);
    }
  }
  return attained;
}

}  // namespace

namespace {

// `tree_a` is a's face tree, `diagonal` its bounding-box diagonal.
HausdorffResult two_sided(const Mesh& a, const FaceTree& tree_a, double diagonal, const Mesh& b,
                          const HausdorffOptions& options, double enough) {
  if (a.faces.empty() || b.faces.empty())
    throw InvalidInputException("Hausdorff distance needs two meshes with faces");
  const double scale = diagonal > 0 ? diagonal : 1;
  const double abs = options.absolute_accuracy * scale;
  const FaceTree tree_b(b);
  double attained = 0;
  enough *= scale;
  const double ab = one_side(a, tree_b, attained, options.relative_accuracy, abs,
                             options.max_refinements, enough);
  const double ba = attained > enough ? attained
                                      : one_side(b, tree_a, attained, options.relative_accuracy,
                                                 abs, options.max_refinements, enough);
  // Bounds from the first direction were judged against a smaller `attained`: still valid.
  return {attained / scale, std::max({ab, ba, attained}) / scale};
}

// A bounded amount of refinement (20,000 triangles per direction): CAD meshes kept exactly by
// the quadrics would otherwise refine their flat sides towards the absolute accuracy for a long
// time.
HausdorffOptions approximation_accuracy() {
  HausdorffOptions accuracy;
  accuracy.max_refinements = 20'000;
  return accuracy;
}

}  // namespace

HausdorffResult hausdorff_distance(const Mesh& a, const Mesh& b, const HausdorffOptions& options) {
  return two_sided(a, FaceTree(a), bounding_box_diagonal(a), b, options,
                   std::numeric_limits<double>::infinity());
}

ApproximationMeasure::ApproximationMeasure(const Mesh& input)
    : input_(input), tree_(input), diagonal_(bounding_box_diagonal(input)) {}

double ApproximationMeasure::distance(const Mesh& approximation) const {
  return two_sided(input_, tree_, diagonal_, approximation, approximation_accuracy(),
                   std::numeric_limits<double>::infinity())
      .distance;
}

bool ApproximationMeasure::within(const Mesh& approximation, double distance) const {
  return two_sided(input_, tree_, diagonal_, approximation, approximation_accuracy(), distance)
             .distance <= distance;
}

double approximation_distance(const Mesh& input, const Mesh& approximation) {
  return ApproximationMeasure(input).distance(approximation);
}

bool approximation_within(const Mesh& input, const Mesh& approximation, double distance) {
  return ApproximationMeasure(input).within(approximation, distance);
}

}  // namespace papernet
