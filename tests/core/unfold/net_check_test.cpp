#include "core/unfold/net_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "core/unfold/unfolding.h"
#include "tests/support/meshes.h"

namespace papernet {
namespace {

bool mentions(const NetCheckReport& report, const std::string& words) {
  for (const std::string& f : report.failures)
    if (f.find(words) != std::string::npos) return true;
  return false;
}

// An overlap-free net of the cube, from the unfolder.
Net cube_net() {
  Unfolding u = Unfolding::steepest_edge(test::cube(), 3);
  Progress quiet;
  EXPECT_TRUE(u.resolve_overlaps({}, quiet));
  return u.net();
}

int a_leaf(const Net& net) {
  std::vector<int> children(net.parent.size(), 0);
  for (int p : net.parent)
    if (p >= 0) ++children[p];
  for (std::size_t f = 0; f < net.parent.size(); ++f)
    if (children[f] == 0 && net.parent[f] >= 0) return static_cast<int>(f);
  return -1;
}

TEST(NetCheck, AcceptsAValidNet) {
  const NetCheckReport report = check_net(test::cube(), cube_net());
  EXPECT_TRUE(report.ok()) << report.summary();
}

TEST(NetCheck, RejectsAFlippedFace) {
  Net net = cube_net();
  const int f = a_leaf(net);
  for (Vec2& p : net.points[f]) p.y = -p.y;  // mirror: congruent edges, reversed orientation
  const NetCheckReport report = check_net(test::cube(), net);
  EXPECT_FALSE(report.ok());
  EXPECT_TRUE(mentions(report, "face " + std::to_string(f) + " is flipped")) << report.summary();
}

TEST(NetCheck, RejectsAGapOnAGluedEdge) {
  Net net = cube_net();
  const int f = a_leaf(net);
  for (Vec2& p : net.points[f]) p = p + Vec2{0.01, 0};  // still congruent, no longer glued
  const NetCheckReport report = check_net(test::cube(), net);
  EXPECT_TRUE(mentions(report, "face " + std::to_string(f) + " is not glued")) << report.summary();
}

TEST(NetCheck, RejectsACycle) {
  Net net = cube_net();
  // Re-point the root to one of its children: no root left, and a cycle of two.
  int root = 0;
  while (net.parent[root] != -1) ++root;
  int child = 0;
  while (net.parent[child] != root) ++child;
  net.parent[root] = child;
  const NetCheckReport report = check_net(test::cube(), net);
  EXPECT_TRUE(mentions(report, "form a cycle")) << report.summary();
  EXPECT_TRUE(mentions(report, "0 roots")) << report.summary();
}

TEST(NetCheck, RejectsAParentThatSharesNoEdge) {
  Net net = cube_net();
  const int f = a_leaf(net);
  // Faces 0 and 2 of the cube are the bottom and top: they share no vertex.
  const int far = f == 2 || f == 3 ? 0 : 2;
  net.parent[f] = far;
  const NetCheckReport report = check_net(test::cube(), net);
  EXPECT_FALSE(report.ok());
}

TEST(NetCheck, RejectsAnOverlappingPair) {
  // The saddle's fan laid out as one path around the centre wraps past 360 degrees.
  const Mesh mesh = test::saddle();
  std::vector<int> parent(mesh.faces.size());
  const int n = 8;
  for (int i = 0; i < n; ++i) parent[i] = i - 1;  // fan: 0 <- 1 <- ... <- 7
  for (int i = 0; i < n; ++i) {
    parent[n + 2 * i] = n + 2 * i + 1;  // outer triangle hangs from its twin
    parent[n + 2 * i + 1] = i;          // which hangs from the fan face
  }
  const Unfolding u(mesh, parent);
  const NetCheckReport report = check_net(mesh, u.net());
  EXPECT_GT(report.overlapping_pairs, 0u);
  EXPECT_TRUE(mentions(report, "overlap")) << report.summary();
}

TEST(NetCheck, RejectsNonCongruentFace) {
  Net net = cube_net();
  net.points[0][0] = net.points[0][0] + Vec2{0.2, 0.1};
  EXPECT_TRUE(mentions(check_net(test::cube(), net), "long in the net"));
}

// The platform's own layout (it is flat) with a breadth-first tree: a valid net.
Net flat_net(const Mesh& mesh) {
  Net net;
  net.parent = test::bfs_net(mesh).parent;
  for (const auto& f : mesh.faces) {
    std::array<Vec2, 3> t;
    for (int k = 0; k < 3; ++k) t[k] = {mesh.vertices[f[k]].x, mesh.vertices[f[k]].y};
    net.points.push_back(t);
  }
  return net;
}

double largest_over_mean_area(const Mesh& mesh) {
  double largest = 0, sum = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    largest = std::max(largest, face_area(mesh, static_cast<int>(f)));
    sum += face_area(mesh, static_cast<int>(f));
  }
  return largest / (sum / static_cast<double>(mesh.faces.size()));
}

TEST(NetCheck, AcceptsANetWithAFaceTenThousandTimesTheMeanArea) {
  // Checks used to end with "face N is far larger than an average face in the net" here.
  const Mesh mesh = test::platform(100, 1000);
  ASSERT_GE(largest_over_mean_area(mesh), 1e4);
  const NetCheckReport report = check_net(mesh, flat_net(mesh));
  EXPECT_TRUE(report.ok()) << report.summary();
}

TEST(NetCheck, FindsAFaceMovedOntoAGiantFace) {
  const Mesh mesh = test::platform(100, 1000);
  Net net = flat_net(mesh);
  // Face 0, a grid triangle at the origin, moved into the middle of the giant face (1,1) (S,0)
  // (S,S): it overlaps that face and nothing else.
  const int giant = static_cast<int>(mesh.faces.size()) - 2;
  for (Vec2& p : net.points[0]) p = p + Vec2{700, 300};
  const NetCheckReport report = check_net(mesh, net);
  EXPECT_EQ(report.overlapping_pairs, 1u) << report.summary();
  EXPECT_TRUE(mentions(report, "face 0 and face " + std::to_string(giant) + " overlap"))
      << report.summary();
}

TEST(NetCheck, AcceptsASliverFlatWithinTheTolerance) {
  // A sliver whose height is below the length tolerance is congruent to its mirror image within
  // that tolerance: laid out either way, it passes (a sign test of its area would fail one).
  Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, 1e-9, 0}};
  mesh.faces = {{0, 1, 2}};
  Net net{{-1}, {{Vec2{0, 0}, Vec2{1, 0}, Vec2{0.5, -1e-9}}}};
  EXPECT_TRUE(check_net(mesh, net).ok()) << check_net(mesh, net).summary();
  // A visible flip still fails.
  net.points[0][2].y = -0.1;
  mesh.vertices[2].y = 0.1;
  EXPECT_TRUE(mentions(check_net(mesh, net), "is flipped")) << check_net(mesh, net).summary();
}

// A fan of six faces around a vertex whose angles add up to a full turn and `excess` radians
// (its rim zigzags up and down), laid out as one path: the last face overlaps the first in a
// wedge `excess` wide at the rim, about excess / 2 deep. Beside it, far off, one face that makes
// the mesh a thousand times wider than the fan.
struct FanBesideAFarFace {
  Mesh mesh;
  Net net;
  std::vector<int> piece;
};

FanBesideAFarFace fan_beside_a_far_face(double excess) {
  // Each apex angle is 60 degrees and excess / 6: rim points at height +-h apart by 60 degrees
  // have cos(angle) = (1/2 - h^2) / (1 + h^2).
  const double angle = std::numbers::pi / 3 + excess / 6;
  const double h = std::sqrt((0.5 - std::cos(angle)) / (1 + std::cos(angle)));
  Mesh fan;
  fan.vertices.push_back({0, 0, 0});
  for (int k = 0; k < 6; ++k)
    fan.vertices.push_back({std::cos(k * std::numbers::pi / 3), std::sin(k * std::numbers::pi / 3),
                            k % 2 == 0 ? h : -h});
  for (int k = 0; k < 6; ++k) fan.faces.push_back({0, 1 + k, 1 + (k + 1) % 6});
  const Net fan_net = Unfolding(fan, {-1, 0, 1, 2, 3, 4}).net();
  Mesh far;
  far.vertices = {{2000, 0, 0}, {2001, 0, 0}, {2000, 1, 0}};
  far.faces = {{0, 1, 2}};
  const Net far_net = Unfolding(far, {-1}).net();
  FanBesideAFarFace out{fan, fan_net, std::vector<int>(6, 0)};
  for (Vec3 v : far.vertices) out.mesh.vertices.push_back(v);
  out.mesh.faces.push_back({7, 8, 9});
  out.net.parent.push_back(-1);
  out.net.points.push_back(far_net.points[0]);
  out.piece.push_back(1);
  return out;
}

TEST(NetCheck, PiecesAreCheckedWithTheWholeMeshsTolerance) {
  // An overlap 1e-5 deep: over a hundred times the tolerance of the fan's own diagonal (2), a
  // tenth of the mesh's (2,000).
  const FanBesideAFarFace small = fan_beside_a_far_face(2e-5);
  const NetCheckReport pieces = check_pieces(small.mesh, small.net, small.piece);
  EXPECT_TRUE(pieces.ok()) << pieces.summary();
  // Checked alone, with its own diagonal, the fan fails.
  Mesh fan = small.mesh;
  fan.faces.pop_back();
  fan.vertices.resize(7);
  Net fan_net = small.net;
  fan_net.parent.pop_back();
  fan_net.points.pop_back();
  EXPECT_TRUE(mentions(check_net(fan, fan_net), "face 0 and face 5 overlap"))
      << check_net(fan, fan_net).summary();
  // An overlap a person would see still fails in the piece, named.
  const FanBesideAFarFace large = fan_beside_a_far_face(0.02);
  const NetCheckReport seen = check_pieces(large.mesh, large.net, large.piece);
  EXPECT_TRUE(mentions(seen, "piece 0: face 0 and face 5 overlap")) << seen.summary();
}

TEST(NetCheck, RejectsWrongSizes) {
  Net net = cube_net();
  net.parent.pop_back();
  EXPECT_FALSE(check_net(test::cube(), net).ok());
}

}  // namespace
}  // namespace papernet
