#include "core/mesh/face_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/io/load.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

// A long thin bar as CAD programs export one: each long side a fan of slivers from its two far
// corners to many points along the other edge, every sliver as long as the bar.
Mesh sliver_bar(double length, double width, double height, int points) {
  Mesh m;
  for (double z : {0.0, height}) {
    const int base = static_cast<int>(m.vertices.size());
    m.vertices.push_back({0, width, z});
    m.vertices.push_back({length, width, z});
    for (int i = 0; i <= points; ++i)
      m.vertices.push_back({length * i / points + (i % 3 == 1 ? 0.3 : 0.0), 0, z});
    // Slivers from (0, width) to the first half of the edge's points, from (length, width) to
    // the rest, and the one between the two corners.
    for (int i = 0; i < points; ++i) {
      const int corner = i < points / 2 ? base : base + 1;
      m.faces.push_back({corner, base + 2 + i, base + 3 + i});
    }
    m.faces.push_back({base, base + 2 + points / 2, base + 1});
  }
  return m;
}

double brute_force(const Mesh& m, Vec3 p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& f : m.faces)
    best = std::min(best,
                    distance2_to_triangle(p, m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]]));
  return best;
}

// Points about the mesh's box, and points on and just off its faces.
void expect_closest_as_brute_force(const Mesh& m, int samples) {
  const FaceTree tree(m);
  Box3 box = Box3::empty();
  for (Vec3 v : m.vertices) box.add(v);
  const Vec3 size = box.size();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.1, 1.1), w(0, 1);
  std::uniform_int_distribution<int> face(0, static_cast<int>(m.faces.size()) - 1);
  for (int s = 0; s < samples; ++s) {
    Vec3 p;
    if (s % 2 == 0) {
      p = {box.lo.x + u(rng) * size.x, box.lo.y + u(rng) * size.y, box.lo.z + u(rng) * size.z};
    } else {
      const auto& f = m.faces[static_cast<std::size_t>(face(rng))];
      double a = w(rng), b = w(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      const Vec3 o = m.vertices[f[0]];
      p = o + a * (m.vertices[f[1]] - o) + b * (m.vertices[f[2]] - o) +
          (0.01 * (w(rng) - 0.5)) * Vec3{size.z, size.x, size.y};
    }
    const double truth = brute_force(m, p);
    const auto [d2, f] = tree.closest(p, s % 3 == 0 ? face(rng) : -1);
    ASSERT_NEAR(d2, truth, 1e-9 * (1 + truth)) << "sample " << s;
    ASSERT_GE(f, 0);
    EXPECT_NEAR(tree.distance2(p, f), truth, 1e-9 * (1 + truth)) << "sample " << s;
  }
}

// Slivers' boxes overlap across much of the bar: the search must still prune none wrongly.
TEST(FaceTree, ClosestFaceOfSliversIsTheBruteForceOne) {
  expect_closest_as_brute_force(sliver_bar(200, 8, 2, 120), 3000);
}

// With `enough2`, a point within it gets a face within it (its distance, not always the least),
// and a point farther gets the closest face, as without it.
TEST(FaceTree, SearchEndsAtAFaceWithinEnough) {
  const Mesh m = sliver_bar(200, 8, 2, 120);
  const FaceTree tree(m);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(-10, 210), y(-4, 12), z(-3, 5);
  int early = 0, exact = 0;
  for (int s = 0; s < 3000; ++s) {
    const Vec3 p{x(rng), y(rng), z(rng)};
    const double truth = brute_force(m, p);
    const double enough2 = 4.0;
    const auto [d2, f] = tree.closest(p, -1, enough2);
    ASSERT_GE(f, 0);
    EXPECT_NEAR(tree.distance2(p, f), d2, 1e-9 * (1 + d2)) << "sample " << s;
    if (truth <= enough2) {
      ASSERT_LE(d2, enough2) << "sample " << s;
      ASSERT_GE(d2, truth - 1e-9 * (1 + truth)) << "sample " << s;
      if (d2 > truth + 1e-9 * (1 + truth)) ++early;
    } else {
      ASSERT_NEAR(d2, truth, 1e-9 * (1 + truth)) << "sample " << s;
      ++exact;
    }
  }
  // Both cases were met, and some searches ended before the closest face.
  EXPECT_GT(early, 0);
  EXPECT_GT(exact, 0);
}

TEST(FaceTree, ClosestFaceOfAMeshIsTheBruteForceOne) {
  expect_closest_as_brute_force(
      load_mesh_file(papernet::test::test_data_dir() + "/sample.obj").mesh, 2000);
}

}  // namespace
}  // namespace papernet
