#include "core/unfold/unfolding.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/io/load.h"
#include "core/mesh/dual_graph.h"
#include "core/unfold/net_check.h"
#include "core/unfold/unfold_tree.h"
#include "tests/support/meshes.h"
#include "tests/support/paths.h"

namespace papernet {

// The Tabu Unfolder's move primitives, for a test of the pre-order they keep.
struct UnfoldingTestAccess {
  static void root_at(Unfolding& u, int r) { u.root_at(r); }
  static int root(const Unfolding& u) { return u.root_; }
  static void cut(Unfolding& u, int g, int other) { u.cut(g, other); }
  static bool in_subtree(const Unfolding& u, int x) { return u.in_subtree(x); }
  static void apply_move(Unfolding& u, int g, int k) { u.apply_move(g, k); }
  static bool same_preorder(const Unfolding& a, const Unfolding& b) {
    return a.order_ == b.order_ && a.tin_ == b.tin_ && a.size_ == b.size_ && a.parent_ == b.parent_;
  }
};

namespace {

namespace fs = std::filesystem;

// Unfolds with TU and checks the net; returns the result.
UnfoldResult unfold_and_check(const Mesh& mesh, std::uint64_t seed = 1, double seconds = 30) {
  TabuOptions options;
  options.seed = seed;
  options.time_limit_seconds = seconds;
  Progress quiet;
  UnfoldResult result = unfold_tabu(mesh, options, quiet);
  EXPECT_TRUE(result.overlap_free) << result.overlaps << " overlapping pairs left";
  const NetCheckReport report = check_net(mesh, result.net);
  EXPECT_TRUE(report.ok()) << report.summary();
  return result;
}

TEST(Unfold, ClosedCube) { unfold_and_check(test::cube()); }

TEST(Unfold, ClosedTorusOfGenusOne) { unfold_and_check(test::torus(24, 12)); }

TEST(Unfold, OpenWavyPatch) {
  unfold_and_check(test::height_field(
      16, [](double x, double y) { return 0.4 * std::sin(3 * x) * std::cos(3 * y); }));
}

TEST(Unfold, SameSeedGivesTheSameNet) {
  const Mesh mesh = test::torus(30, 10);
  const UnfoldResult a = unfold_and_check(mesh, 7), b = unfold_and_check(mesh, 7);
  EXPECT_EQ(a.net.parent, b.net.parent);
  ASSERT_EQ(a.net.points.size(), b.net.points.size());
  for (std::size_t f = 0; f < a.net.points.size(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(a.net.points[f][k] == b.net.points[f][k]) << f;
}

TEST(Unfold, SaddleOverlapIsDetectedAndResolved) {
  const Mesh mesh = test::saddle();
  const int n = 8;
  Unfolding u(mesh, test::saddle_path_tree(n));
  EXPECT_GT(u.overlap_count(), 0u);  // the centre's angle sum is above 360 degrees
  bool fan_pair = false;
  for (int f : u.overlapping_faces()) fan_pair = fan_pair || f < n;
  EXPECT_TRUE(fan_pair);
  Progress quiet;
  TabuOptions options;
  options.time_limit_seconds = 10;
  EXPECT_TRUE(u.resolve_overlaps(options, quiet));
  EXPECT_EQ(u.overlap_count(), 0u);
  const NetCheckReport report = check_net(mesh, u.net());
  EXPECT_TRUE(report.ok()) << report.summary();
}

TEST(Unfold, IncrementalOverlapCountMatchesARecount) {
  const Mesh mesh = test::saddle(12, 0.5);
  Unfolding u = Unfolding::steepest_edge(mesh, 5);
  EXPECT_GT(u.overlap_count(), 0u);
  Progress quiet;
  TabuOptions options;
  for (std::size_t budget : {1, 2, 5, 20}) {
    options.max_iterations = budget;
    u.resolve_overlaps(options, quiet);
    const Unfolding fresh(mesh, u.net().parent);
    EXPECT_EQ(u.overlap_count(), fresh.overlap_count()) << "after " << budget;
    EXPECT_EQ(u.overlap_count(), check_net(mesh, u.net()).overlapping_pairs) << "after " << budget;
  }
}

TEST(Unfold, RefusesBrokenInput) {
  Mesh twisted = test::cube();
  std::swap(twisted.faces[0][0], twisted.faces[0][1]);  // inconsistently oriented
  EXPECT_THROW(Unfolding::steepest_edge(twisted, 1), InvalidInputException);
  Mesh two = test::cube();
  for (const auto& f : test::cube().faces) two.faces.push_back({f[0] + 8, f[1] + 8, f[2] + 8});
  for (const Vec3& v : test::cube().vertices) two.vertices.push_back(v + Vec3{3, 0, 0});
  EXPECT_THROW(Unfolding::steepest_edge(two, 1), InvalidInputException);  // two pieces
  std::vector<int> parent(12, 0);
  parent[0] = -1;  // faces 2.. do not share an edge with face 0
  EXPECT_THROW(Unfolding(test::cube(), parent), TopologyException);
  EXPECT_THROW(Unfolding(test::cube(), std::vector<int>(12, -1)), TopologyException);
}

// A vertex split as progressive unfolding does it: face 0 of the cube becomes three faces
// around a new vertex; the new faces go between linked pairs or hang as leaves.
TEST(Unfold, EditsAndUpdateKeepTheStateConsistent) {
  const Mesh cube = test::cube();
  Unfolding u = Unfolding::steepest_edge(cube, 11);
  Progress quiet;
  ASSERT_TRUE(u.resolve_overlaps({}, quiet));
  const auto old = cube.faces[0];  // (0, 2, 1), bottom
  const int v = u.add_vertex({2.0 / 3, 1.0 / 3, -0.05});
  const int across12 = u.neighbour(0, 1), across10 = u.neighbour(0, 2);
  u.set_face_corners(0, {old[0], old[1], v});
  const int f1 = u.add_face({old[1], old[2], v});
  const int f2 = u.add_face({old[2], old[0], v});
  for (const auto& [f, n] : {std::pair{f1, across12}, std::pair{f2, across10}}) {
    if (u.linked(0, n))
      u.insert_between(f, n, 0);
    else
      u.attach(f, 0);
  }
  const std::size_t overlaps = u.update();
  EXPECT_EQ(u.face_count(), 14u);
  NetCheckReport report = check_net(u.mesh(), u.net());
  EXPECT_EQ(report.failure_count, report.overlapping_pairs) << report.summary();
  EXPECT_EQ(overlaps, report.overlapping_pairs);

  u.set_vertex_position(v, {0.5, 0.5, -0.3});
  EXPECT_EQ(u.update(), Unfolding(u.mesh(), u.net().parent).overlap_count());
  ASSERT_TRUE(u.resolve_overlaps({}, quiet));
  report = check_net(u.mesh(), u.net());
  EXPECT_TRUE(report.ok()) << report.summary();
}

TEST(Unfold, UpdateRefusesAFaceLeftOutOfTheTree) {
  Unfolding u = Unfolding::steepest_edge(test::cube(), 1);
  const int v = u.add_vertex({0.5, 0.5, -0.1});
  const auto old = u.mesh().faces[0];
  u.set_face_corners(0, {old[0], old[1], v});
  u.add_face({old[1], old[2], v});
  EXPECT_THROW(u.update(), TopologyException);
}

// Small edits of a large net take update()'s local path (only the parts of the tree cut off by
// the edited faces move): the state must match a fresh build of the same tree every time, and
// broken trees are still refused.
TEST(Unfold, SmallEditsOfALargeNetMatchAFreshBuild) {
  const Mesh mesh = test::torus(40, 16);  // 1,280 faces
  Unfolding u = Unfolding::steepest_edge(mesh, 3);
  const auto expect_fresh = [&u](const std::string& what) {
    const Unfolding fresh(u.mesh(), u.net().parent);
    EXPECT_EQ(u.overlap_count(), fresh.overlap_count()) << what;
    std::vector<int> faces = u.overlapping_faces(), fresh_faces = fresh.overlapping_faces();
    std::sort(faces.begin(), faces.end());
    std::sort(fresh_faces.begin(), fresh_faces.end());
    EXPECT_EQ(faces, fresh_faces) << what;
    // The same layout up to a rigid motion (the local update keeps its largest part in place,
    // a fresh build lays out from the root): corners at the same distances from face 0's.
    const Triangle2& a = u.points(0);
    const Triangle2& b = fresh.points(0);
    double worst = 0;
    for (int f = 0; f < static_cast<int>(u.face_count()); ++f)
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
          worst = std::max(worst,
                           std::abs(norm(u.points(f)[k] - a[j]) - norm(fresh.points(f)[k] - b[j])));
    EXPECT_LT(worst, 1e-9) << what;
    const NetCheckReport report = check_net(u.mesh(), u.net());
    EXPECT_EQ(report.failure_count, report.overlapping_pairs) << what << ": " << report.summary();
  };
  expect_fresh("start");
  for (int v = 0; v < static_cast<int>(mesh.vertices.size()); v += 97) {
    const Vec3 p = u.mesh().vertices[v];
    u.set_vertex_position(v, {p.x * 1.05, p.y * 0.97, p.z + 0.08});
    u.update();
    expect_fresh("vertex " + std::to_string(v) + " moved");
  }
  // Re-hang faces (with their subtrees) from another neighbour outside their subtree.
  int moves = 0;
  for (int f = 0; f < static_cast<int>(u.face_count()) && moves < 10; f += 37) {
    for (int k = 0; k < 3; ++k) {
      const int q = u.neighbour(f, k);
      bool inside = false;
      for (int x = q; x >= 0 && !inside; x = u.parent(x)) inside = x == f;
      if (q < 0 || q == u.parent(f) || u.parent(f) < 0 || inside) continue;
      u.attach(f, q);
      u.update();
      expect_fresh("face " + std::to_string(f) + " re-hung");
      ++moves;
      break;
    }
  }
  EXPECT_GT(moves, 0);
  // Hanging a face from its own child makes a cycle.
  for (int f = 0; f < static_cast<int>(u.face_count()); ++f) {
    int child = -1;
    for (int k = 0; k < 3; ++k)
      if (u.neighbour(f, k) >= 0 && u.parent(u.neighbour(f, k)) == f) child = u.neighbour(f, k);
    if (child < 0 || u.parent(f) < 0) continue;
    u.attach(f, child);
    EXPECT_THROW(u.update(), TopologyException);
    break;
  }
}

// Overlapping faces and pair count by brute force over all pairs, with Unfolding's own test.
std::pair<std::vector<int>, std::size_t> brute_force_overlaps(const Unfolding& u) {
  const int nf = static_cast<int>(u.face_count());
  std::vector<char> hit(nf, 0);
  std::size_t pairs = 0;
  for (int a = 0; a < nf; ++a)
    for (int b = a + 1; b < nf; ++b)
      if (triangles_overlap(u.points(a), u.points(b), u.tolerance())) {
        hit[a] = hit[b] = 1;
        ++pairs;
      }
  std::vector<int> faces;
  for (int f = 0; f < nf; ++f)
    if (hit[f]) faces.push_back(f);
  return {faces, pairs};
}

// update()'s local path on a real 2,000-face net: edits of a few vertices at once cut the tree
// into many parts that move rigidly; each part is tested as a whole against the rest (its own
// faces out of the grid), the edited faces one by one. The overlapping pairs must be exactly
// those of a brute-force test of all pairs, after every edit.
TEST(Unfold, LocalUpdatesOfARealNetMatchBruteForce) {
  const fs::path file =
      fs::path(papernet::test::shared_data_dir()) / "bench" / "2000" / "draco__bun_zipper.obj";
  if (!fs::exists(file)) GTEST_SKIP() << "needs ../shared/data: " << file.string();
  const Mesh mesh = load_mesh_file(file.string()).mesh;
  Unfolding u = Unfolding::steepest_edge(mesh, 1);
  const int nv = static_cast<int>(mesh.vertices.size());
  std::size_t relaid = u.relaid_faces(), with_overlaps = 0;
  for (int round = 0; round < 8; ++round) {
    // Four vertices pulled outwards by 30 % of their distance from vertex 0.
    for (int j = 0; j < 4; ++j) {
      const int v = (round * 131 + j * 257) % nv;
      const Vec3 o = u.mesh().vertices[0], p = u.mesh().vertices[v];
      u.set_vertex_position(v, o + 1.3 * (p - o));
    }
    u.update();
    const auto [faces, pairs] = brute_force_overlaps(u);
    std::vector<int> have = u.overlapping_faces();
    std::sort(have.begin(), have.end());
    EXPECT_EQ(u.overlap_count(), pairs) << "round " << round;
    EXPECT_EQ(have, faces) << "round " << round;
    if (pairs > 0) ++with_overlaps;
  }
  // The local path ran (it moves far fewer than all faces per edit), and the edits made overlaps.
  EXPECT_LT(u.relaid_faces() - relaid, 8 * u.face_count());
  EXPECT_GT(with_overlaps, 0u);
}

// After a move the Tabu Unfolder keeps the tree's pre-order, subtree sizes and parents up to
// date (moving the pre-order range of the re-hung subtree, or recomputing them all when the
// root's side moves): they must be exactly what a fresh root_at gives, after every move.
TEST(Unfold, PreorderAfterMovesMatchesAFreshOne) {
  const fs::path file =
      fs::path(papernet::test::shared_data_dir()) / "bench" / "800" / "c3d__spot.obj";
  if (!fs::exists(file)) GTEST_SKIP() << "needs ../shared/data: " << file.string();
  Unfolding u = Unfolding::steepest_edge(load_mesh_file(file.string()).mesh, 1);
  using A = UnfoldingTestAccess;
  const int nf = static_cast<int>(u.face_count());
  int root = 0;
  while (u.parent(root) != -1) root = u.parent(root);
  A::root_at(u, root);
  std::size_t moves[2] = {0, 0};  // [1]: g's own subtree re-hung, [0]: the side of the root
  for (int step = 0; step < 4000 && moves[0] + moves[1] < 300; ++step) {
    const int g = (step * 7919) % nf;
    // The link to g's parent, or to one of its children.
    int other = u.parent(g);
    if (step % 2 == 0)
      for (int k = 0; k < 3; ++k) {
        const int n = u.neighbour(g, k);
        if (n >= 0 && u.parent(n) == g) other = n;
      }
    if (other < 0) continue;
    const bool own_subtree = other == u.parent(g);
    A::cut(u, g, other);
    for (int k = 0; k < 3; ++k) {
      const int q = u.neighbour(g, k);
      if (q < 0 || u.linked(g, q) || A::in_subtree(u, q)) continue;
      A::apply_move(u, g, k);
      ++moves[own_subtree ? 1 : 0];
      Unfolding fresh = u;
      A::root_at(fresh, A::root(u));
      ASSERT_TRUE(A::same_preorder(u, fresh)) << "after move " << moves[0] + moves[1];
      break;
    }
  }
  EXPECT_GT(moves[1], 50u);
  EXPECT_GT(moves[0], 5u);
}

void unfold_folder(const fs::path& dir, std::size_t max_faces) {
  std::size_t done = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".obj" && ext != ".off" && ext != ".ply" && ext != ".stl" && ext != ".glb" &&
        ext != ".gltf" && ext != ".drc")
      continue;
    LoadedMesh loaded;
    try {
      loaded = load_mesh_file(entry.path().string());
    } catch (const IOException& e) {
      std::cout << "[ NOTE     ] not unfolded, the loader cannot read it yet: " << entry.path()
                << ": " << e.what() << "\n";
      continue;
    }
    if (loaded.mesh.faces.size() > max_faces) {
      std::cout << "[ NOTE     ] not unfolded, over " << max_faces << " faces: " << entry.path()
                << "\n";
      continue;
    }
    SCOPED_TRACE(entry.path().string());
    unfold_and_check(loaded.mesh);
    ++done;
  }
  EXPECT_GT(done, 0u);
}

TEST(Unfold, EveryMeshInTestData) {
  const fs::path dir = papernet::test::test_data_dir();
  if (!fs::is_directory(dir)) GTEST_SKIP() << "needs tests/data (added by the loader branch)";
  unfold_folder(dir, 5000);
}

// The organic meshes of the benchmark set at 400 faces. (The CAD meshes with long slivers,
// where plain TU may run out of budget, are measured by `papernet bench`, not asserted here.)
TEST(Unfold, BenchMeshesAt400Faces) {
  const fs::path dir = fs::path(papernet::test::shared_data_dir()) / "bench" / "400";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "needs ../shared/data: bench/400";
  for (const char* name : {"c3d__spot", "c3d__igea", "c3d__homer", "c3d__fandisk",
                           "draco__bun_zipper", "trimesh__torus", "thingi10k__1706459"}) {
    SCOPED_TRACE(name);
    const LoadedMesh loaded = load_mesh_file((dir / (std::string(name) + ".obj")).string());
    unfold_and_check(loaded.mesh);
  }
}

// Total length of the mesh edges that `parent` cuts (interior edges whose faces are not linked).
double cut_length(const Mesh& mesh, const DualGraph& graph, const std::vector<int>& parent) {
  double total = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int q = graph.neighbour[f][k];
      if (q < static_cast<int>(f) || parent[f] == q || parent[q] == static_cast<int>(f)) continue;
      total += norm(mesh.vertices[mesh.faces[f][(k + 1) % 3]] - mesh.vertices[mesh.faces[f][k]]);
    }
  return total;
}

TEST(UnfoldTree, MinPerimeterTreeCutsTheShortestEdges) {
  const Mesh mesh = test::torus(24, 12, 2, 0.3);  // long edges around, short ones across
  const DualGraph graph = build_dual_graph(mesh);
  const std::vector<int> tree = min_perimeter_tree(mesh, graph, 1);
  EXPECT_NO_THROW(Unfolding(mesh, tree));  // a spanning tree of adjacent faces
  const double shortest = cut_length(mesh, graph, tree);
  for (std::uint64_t seed = 1; seed <= 5; ++seed)
    EXPECT_LT(shortest, cut_length(mesh, graph, steepest_edge_tree(mesh, graph, seed))) << seed;
  EXPECT_DOUBLE_EQ(shortest, cut_length(mesh, graph, min_perimeter_tree(mesh, graph, 9)));
}

// CAD parts with long slivers and large flat regions at 400 faces. The plain Tabu Unfolder
// wandered on plateaus of ~100 overlapping pairs here for a whole minute (its best move on a
// walk was often a large step up); the better-of-two start and the extra walks when stalled
// resolve them. Same seed, same net, also on this path.
TEST(Unfold, CadSliverMeshesAt400Faces) {
  const fs::path dir = fs::path(papernet::test::shared_data_dir()) / "bench" / "400";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "needs ../shared/data: bench/400";
  for (const char* name : {"thingi10k__73416", "trimesh__ADIS16480", "trimesh__1002_tray_bottom"}) {
    SCOPED_TRACE(name);
    const LoadedMesh loaded = load_mesh_file((dir / (std::string(name) + ".obj")).string());
    const UnfoldResult a = unfold_and_check(loaded.mesh, 3), b = unfold_and_check(loaded.mesh, 3);
    EXPECT_EQ(a.net.parent, b.net.parent);
  }
}

// A CAD tray of long slivers at 800 faces, with half the walks going towards a face the start
// face overlaps (every cut then separates that pair): a net within an iteration budget, not time,
// so the outcome is the same on any machine. It used to compare with the paper's walks at 2,000
// iterations, but that compared two single trajectories, which are chaotic: since the overlap
// lists are read in face order, seed 1 needs 2,510 iterations instead of 1,627 (seeds 1-6:
// 2,510-6,898; before: 1,627-7,824). The difference between the walks shows on the benchmark
// (thingi10k__79741 at 2,000 faces, docs/performance.md).
TEST(Unfold, WalksTowardsAnOverlappingFaceResolveACadTray) {
  const fs::path file = fs::path(papernet::test::shared_data_dir()) / "bench" / "800" /
                        "trimesh__1002_tray_bottom.obj";
  if (!fs::exists(file)) GTEST_SKIP() << "needs ../shared/data: " << file.string();
  const Mesh mesh = load_mesh_file(file.string()).mesh;
  TabuOptions options;
  options.seed = 1;
  options.max_iterations = 4000;
  options.time_limit_seconds = 0;
  Progress quiet;
  ASSERT_GT(options.partner_walks, 0.0);
  const UnfoldResult with = unfold_tabu(mesh, options, quiet);
  EXPECT_TRUE(with.overlap_free) << with.overlaps << " pairs left";
  EXPECT_LT(with.stats.iterations, options.max_iterations);
  const NetCheckReport report = check_net(mesh, with.net);
  EXPECT_TRUE(report.ok()) << report.summary();
}

// The Twin plate (5,756 faces, aspect ratios up to 1.6e8, a long bar whose sides are fans of
// slivers): the minimum-perimeter tree lays its flat sides out as they are; what overlapped
// there before was rounding of the float input (pairs of faces adjacent in 3D, 1e-8 of the
// diagonal deep), which the overlap test now ignores as the net checker does.
TEST(Unfold, TwinPlateOfSliversUnfolds) {
  const fs::path file = fs::path(papernet::test::shared_data_dir()) / "bench" / "100" /
                        "manifold__Generic_Twin_7081.1.t0_right.obj";
  if (!fs::exists(file)) GTEST_SKIP() << "needs ../shared/data: " << file.string();
  unfold_and_check(load_mesh_file(file.string()).mesh, 1, 20);
}

// An open fan of 7 triangles with 60° at the centre (420° laid flat): its dual graph is a path,
// so its only edge unfolding is the fan itself, which overlaps. TU says so at once.
TEST(Unfold, MeshWhoseOnlyUnfoldingOverlapsIsRefused) {
  Mesh fan;
  fan.vertices.push_back({0, 0, 0});
  const double h = std::sqrt((std::cos(M_PI / 4) - 0.5) / (1 + std::cos(M_PI / 4)));
  for (int i = 0; i <= 7; ++i) {
    const double r = std::sqrt(1 - h * h), a = i * M_PI / 4;
    fan.vertices.push_back({r * std::cos(a), r * std::sin(a), i % 2 ? h : -h});
  }
  for (int i = 0; i < 7; ++i) fan.faces.push_back({0, i + 1, i + 2});
  TabuOptions options;
  options.time_limit_seconds = 60;
  Progress quiet;
  try {
    unfold_tabu(fan, options, quiet);
    ADD_FAILURE() << "no InvalidInputException";
  } catch (const InvalidInputException& e) {
    EXPECT_NE(std::string(e.what()).find("dual graph is a tree"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace papernet
