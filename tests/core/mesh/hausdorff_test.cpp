#include "core/mesh/hausdorff.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/errors.h"
#include "core/io/load.h"
#include "core/mesh/decimate.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

// Axis-aligned box surface with corners lo and hi, 12 outward-facing triangles.
Mesh box(Vec3 lo, Vec3 hi) {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
  m.faces = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
             {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

void expect_bracketed(const HausdorffResult& r, double truth) {
  EXPECT_LE(r.distance, truth * (1 + 1e-12));
  EXPECT_GE(r.upper_bound, truth * (1 - 1e-12));
  EXPECT_LE(r.upper_bound, r.distance * 1.01 + 1e-12);
}

TEST(Hausdorff, IdenticalMeshesAreAtZero) {
  const Mesh m = box({0, 0, 0}, {1, 2, 3});
  const HausdorffResult r = hausdorff_distance(m, m);
  EXPECT_EQ(r.distance, 0);
  EXPECT_LE(r.upper_bound, 1e-7);
}

TEST(Hausdorff, NestedCubesAreCornerToCornerApart) {
  // Outer corner (1,1,1) is sqrt(3)/2 from the inner cube; relative to the inner diagonal sqrt(3).
  const Mesh inner = box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5});
  const Mesh outer = box({-1, -1, -1}, {1, 1, 1});
  expect_bracketed(hausdorff_distance(inner, outer), 0.5);
  // Relative to the outer diagonal 2 sqrt(3) it is half of that, whichever side is first.
  expect_bracketed(hausdorff_distance(outer, inner), 0.25);
}

TEST(Hausdorff, FarthestPointInsideAFaceIsFoundToOnePercent) {
  // A unit equilateral triangle against three small triangles cut off its corners: the farthest
  // point is the centroid (never a midpoint-subdivision vertex), at 1/sqrt(3) - eps sqrt(3)/2.
  const double eps = 0.01, h = std::sqrt(3.0) / 2;
  Mesh a, b;
  a.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, h, 0}};
  a.faces = {{0, 1, 2}};
  for (int i = 0; i < 3; ++i) {
    const Vec3 p = a.vertices[i], q = a.vertices[(i + 1) % 3], r = a.vertices[(i + 2) % 3];
    const int base = static_cast<int>(b.vertices.size());
    b.vertices.push_back(p);
    b.vertices.push_back(p + eps * (q - p));
    b.vertices.push_back(p + eps * (r - p));
    b.faces.push_back({base, base + 1, base + 2});
  }
  const double diagonal = std::sqrt(1 + h * h);
  expect_bracketed(hausdorff_distance(a, b), (1 / std::sqrt(3.0) - eps * h) / diagonal);
}

TEST(Hausdorff, ParallelPlanesAreTheirOffsetApart) {
  Mesh a, b;
  a.vertices = {{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}};
  a.faces = {{0, 1, 2}, {0, 2, 3}};
  b = a;
  for (Vec3& p : b.vertices) p.z = 0.25;
  b.faces = {{0, 1, 3}, {1, 2, 3}};  // the other diagonal
  expect_bracketed(hausdorff_distance(a, b), 0.25 / 5);
}

TEST(Hausdorff, DecimatedMeshAgreesWithDenseSampling) {
  const Mesh input = load_mesh_file(papernet::test::test_data_dir() + "/sample.obj").mesh;
  Progress progress;
  const Mesh coarse = decimate(input, {CollapseStrategy::SEMP, 0}, progress).compact();
  const HausdorffResult r = hausdorff_distance(input, coarse);
  EXPECT_GT(r.distance, 0);
  EXPECT_LE(r.upper_bound, r.distance * 1.01);
  // Brute force from the coarse side: a 12x12 barycentric grid per face against every input face.
  // It is attained by sample points, so it cannot exceed the upper bound.
  double brute = 0;
  for (const auto& f : coarse.faces)
    for (int i = 0; i <= 12; ++i)
      for (int j = 0; i + j <= 12; ++j) {
        const Vec3 p = (1 - (i + j) / 12.0) * coarse.vertices[f[0]] +
                       (i / 12.0) * coarse.vertices[f[1]] + (j / 12.0) * coarse.vertices[f[2]];
        double best = 1e300;
        for (const auto& g : input.faces) {
          // Distance to the triangle through its plane projection or its edges.
          const Vec3 a = input.vertices[g[0]], b = input.vertices[g[1]], c = input.vertices[g[2]];
          auto seg = [&](Vec3 s, Vec3 t) {
            const Vec3 st = t - s;
            const double u = std::clamp(dot(p - s, st) / dot(st, st), 0.0, 1.0);
            return norm(p - (s + u * st));
          };
          double d = std::min({seg(a, b), seg(b, c), seg(c, a)});
          const Vec3 n = cross(b - a, c - a);
          const double nn = dot(n, n);
          if (nn > 0) {
            const Vec3 q = p - (dot(p - a, n) / nn) * n;
            if (dot(cross(b - a, q - a), n) >= 0 && dot(cross(c - b, q - b), n) >= 0 &&
                dot(cross(a - c, q - c), n) >= 0)
              d = std::min(d, norm(p - q));
          }
          best = std::min(best, d);
        }
        brute = std::max(brute, best);
      }
  brute /= bounding_box_diagonal(input);
  EXPECT_LE(brute, r.upper_bound * (1 + 1e-9));
  EXPECT_GT(brute, 0.5 * r.distance);  // the dense samples see most of it
}

// A plate fanned into long slivers (as CAD programs export flat faces) against two triangles
// parallel to it: every point is the offset apart, found exactly although most closest-face
// searches end at the first sliver within half the distance already attained.
TEST(Hausdorff, SliverFannedPlatesAreTheirOffsetApart) {
  Mesh fan;
  const int points = 200;
  fan.vertices = {{0, 3, 0}, {4, 3, 0}};
  for (int i = 0; i <= points; ++i) fan.vertices.push_back({4.0 * i / points, 0, 0});
  for (int i = 0; i < points; ++i) fan.faces.push_back({i < points / 2 ? 0 : 1, 2 + i, 3 + i});
  fan.faces.push_back({0, 2 + points / 2, 1});
  Mesh plate;
  plate.vertices = {{0, 0, 0.25}, {4, 0, 0.25}, {4, 3, 0.25}, {0, 3, 0.25}};
  plate.faces = {{0, 1, 2}, {0, 2, 3}};
  expect_bracketed(hausdorff_distance(fan, plate), 0.25 / 5);
  expect_bracketed(hausdorff_distance(plate, fan), 0.25 / 5);
  EXPECT_NEAR(approximation_distance(fan, plate), 0.25 / 5, 1e-12);
  EXPECT_TRUE(approximation_within(fan, plate, 0.0501));
  EXPECT_FALSE(approximation_within(fan, plate, 0.0499));
}

// The yes-or-no question answers as the distance does, on both sides of it: the decimated sample
// mesh, and the nested cubes (whose farthest points are corners, found before any refinement).
TEST(Hausdorff, WithinADistanceAgreesWithTheDistance) {
  const Mesh input = load_mesh_file(papernet::test::test_data_dir() + "/sample.obj").mesh;
  Progress progress;
  const Mesh coarse = decimate(input, {CollapseStrategy::SEMP, 0}, progress).compact();
  const double d = approximation_distance(input, coarse);
  ASSERT_GT(d, 0);
  EXPECT_TRUE(approximation_within(input, coarse, 1.02 * d));
  EXPECT_FALSE(approximation_within(input, coarse, 0.98 * d));
  const Mesh inner = box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5});
  const Mesh outer = box({-1, -1, -1}, {1, 1, 1});
  EXPECT_TRUE(approximation_within(inner, outer, 0.5));
  EXPECT_FALSE(approximation_within(inner, outer, 0.49));
  EXPECT_TRUE(approximation_within(inner, inner, 0));
}

TEST(Hausdorff, EmptyMeshIsRefused) {
  EXPECT_THROW(hausdorff_distance(Mesh{}, box({0, 0, 0}, {1, 1, 1})), InvalidInputException);
}

}  // namespace
}  // namespace papernet
