#include "core/tabs/tab_clearance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <numeric>

#include "core/io/load.h"
#include "core/mesh/angle_defects.h"
#include "core/tabs/tab_clearance_report.h"
#include "core/unfold/net_check.h"
#include "core/unfold/progressive.h"
#include "core/unfold/unfolding.h"
#include "tests/support/meshes.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

/// The Tabu Unfolder's net of a tests/data mesh, and the lowest printable tab (2 mm) in model
/// units when the mesh is printed 200 mm long.
struct Case {
  Mesh mesh;
  Net net;
  double min_height = 0;
};

Case unfolded(const std::string& file) {
  for (auto& [name, mesh] : test::test_data_meshes()) {
    if (name != file) continue;
    Progress quiet;
    TabuOptions options;
    options.time_limit_seconds = 600;  // against a hang only: ASan on a loaded machine is slow
    Case c{mesh, unfold_tabu(mesh, options, quiet).net, 0};
    Vec3 lo = mesh.vertices[0], hi = lo;
    for (const Vec3& v : mesh.vertices) {
      lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
      hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
    }
    c.min_height = 2.0 / (200.0 / std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}));
    return c;
  }
  ADD_FAILURE() << "tests/data has no " << file;
  return {};
}

TEST(TabClearance, OpensNearSlitsAndKeepsTheNetValid) {
  const Case c = unfolded("sample.obj");
  ASSERT_FALSE(c.mesh.faces.empty());
  TabClearanceOptions options;
  options.min_height = c.min_height;
  const std::size_t blocked = edges_without_tab_room(c.mesh, c.net, options).size();
  ASSERT_GT(blocked, 50u) << "sample.obj's dense net has near-slits";
  Progress quiet;
  const TabClearanceResult r = clear_tab_room(c.mesh, c.net, options, quiet);
  EXPECT_EQ(r.blocked_before, blocked);
  EXPECT_LT(r.blocked_after, blocked / 2);
  EXPECT_GT(r.moves, 0u);
  // What the pass says is what an independent recount of its net finds.
  const std::vector<EdgeSide> left = edges_without_tab_room(c.mesh, r.net, options);
  EXPECT_EQ(left.size(), r.blocked_after);
  const NetCheckReport check = check_net(c.mesh, r.net);
  EXPECT_TRUE(check.ok()) << check.summary();
  // Deterministic: the same net and options give the same net (at a tenth of the budget;
  // KicksOpenEdgesTheSearchLeavesBlocked repeats a whole run, kicks included).
  TabClearanceOptions brief = options;
  brief.max_evaluations = 10'000;
  const TabClearanceResult once = clear_tab_room(c.mesh, c.net, brief, quiet);
  const TabClearanceResult again = clear_tab_room(c.mesh, c.net, brief, quiet);
  EXPECT_GT(once.moves, 0u);
  EXPECT_EQ(again.net.parent, once.net.parent);
  ASSERT_EQ(again.net.points.size(), once.net.points.size());
  for (std::size_t f = 0; f < once.net.points.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(again.net.points[f][k].x, once.net.points[f][k].x);
      EXPECT_EQ(again.net.points[f][k].y, once.net.points[f][k].y);
    }
  // Keeping the net inside its box: no face leaves the input's bounding box.
  brief.keep_bounds = true;
  const TabClearanceResult boxed = clear_tab_room(c.mesh, c.net, brief, quiet);
  EXPECT_LT(boxed.blocked_after, blocked);
  EXPECT_TRUE(check_net(c.mesh, boxed.net).ok());
  const auto box = [](const Net& net) {
    Vec2 lo = net.points[0][0], hi = lo;
    for (const auto& t : net.points)
      for (Vec2 p : t)
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)},
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    return std::pair{lo, hi};
  };
  const auto [lo0, hi0] = box(c.net);
  const auto [lo1, hi1] = box(boxed.net);
  const double eps = 1e-9 * (hi0.x - lo0.x + hi0.y - lo0.y);
  EXPECT_GE(lo1.x, lo0.x - eps);
  EXPECT_GE(lo1.y, lo0.y - eps);
  EXPECT_LE(hi1.x, hi0.x + eps);
  EXPECT_LE(hi1.y, hi0.y + eps);
  // A smaller budget stops earlier, and never leaves more than it started with.
  options.max_evaluations = 10;
  const TabClearanceResult short_run = clear_tab_room(c.mesh, c.net, options, quiet);
  EXPECT_LE(short_run.evaluations, 20u);  // 10, and 10 for the second round
  EXPECT_LE(short_run.blocked_after, blocked);
  EXPECT_GE(short_run.blocked_after, r.blocked_after);
  // A clock limit (the service's job deadline) stops it too, with a valid net no worse than
  // the input: a nanosecond leaves time for one step of at most a few hundred candidates.
  options.max_evaluations = 100'000;
  options.time_limit_seconds = 1e-9;
  const TabClearanceResult timed = clear_tab_room(c.mesh, c.net, options, quiet);
  EXPECT_LT(timed.evaluations, r.evaluations / 10);
  EXPECT_LE(timed.blocked_after, blocked);
  EXPECT_TRUE(check_net(c.mesh, timed.net).ok());
}

// The job keeps time after the pass for each edge still without room (the print nests a glue
// strip for each): when that time is more than the pass's limit, the pass returns the input net
// without a move; when it is less, the pass searches as before.
TEST(TabClearance, TheTimeKeptForEachEdgeWithoutRoomStopsThePassFirst) {
  const Case c = unfolded("sample.obj");
  ASSERT_FALSE(c.mesh.faces.empty());
  TabClearanceOptions options;
  options.min_height = c.min_height;
  options.max_evaluations = 2'000;
  options.time_limit_seconds = 600;
  const std::size_t blocked = edges_without_tab_room(c.mesh, c.net, options).size();
  ASSERT_GT(blocked, 50u) << "sample.obj's dense net has near-slits";
  Progress quiet;
  options.seconds_per_blocked_edge = 2 * options.time_limit_seconds / double(blocked);
  const TabClearanceResult kept = clear_tab_room(c.mesh, c.net, options, quiet);
  EXPECT_EQ(kept.blocked_before, blocked);
  EXPECT_EQ(kept.evaluations, 0u);
  EXPECT_EQ(kept.moves, 0u);
  EXPECT_EQ(kept.kicks, 0u);
  EXPECT_EQ(kept.blocked_after, blocked);
  EXPECT_EQ(kept.net.parent, c.net.parent);
  // A millisecond an edge: time enough for the whole budget.
  options.seconds_per_blocked_edge = 1e-3;
  const TabClearanceResult searched = clear_tab_room(c.mesh, c.net, options, quiet);
  EXPECT_GT(searched.moves, 0u);
  EXPECT_LT(searched.blocked_after, blocked);
  EXPECT_TRUE(check_net(c.mesh, searched.net).ok());
}

// Where the blocked edges are: leaves of the cut tree at nearly flat vertices (their two sides
// meet at the vertex's angle defect) and hairs; the pass turns flat leaves into path vertices.
TEST(TabClearance, FlatLeavesAreNearSlitsAndThePassRemovesThem) {
  const Case c = unfolded("sample.obj");
  ASSERT_FALSE(c.mesh.faces.empty());
  TabClearanceOptions options;
  options.min_height = c.min_height;
  const double flat = 10 * std::numbers::pi / 180;
  const TabRoomReport before = describe_tab_room(c.mesh, c.net, options, flat);
  EXPECT_EQ(before.blocked, edges_without_tab_room(c.mesh, c.net, options).size());
  EXPECT_EQ(before.blocked, before.blocked_leaf + before.blocked_hair + before.blocked_other);
  EXPECT_GT(before.blocked_leaf, before.blocked / 3);
  EXPECT_EQ(before.boundary_vertices, 0u);  // a closed mesh
  // Every leaf at a vertex with a defect under 2 degrees is a near-slit at 200 mm, and many
  // leaves are such leaves on this smooth mesh (about half of the Tabu Unfolder's net's).
  const auto count = [](const std::vector<std::size_t>& by_degree, std::size_t lo, std::size_t hi) {
    return std::accumulate(by_degree.begin() + lo, by_degree.begin() + hi, std::size_t{0});
  };
  EXPECT_GT(count(before.leaf_defects, 0, 2), before.leaves / 3);
  EXPECT_EQ(count(before.blocked_leaf_defects, 0, 2), count(before.leaf_defects, 0, 2));
  EXPECT_LE(before.flat_leaves, before.leaves);

  Progress quiet;
  const TabClearanceResult r = clear_tab_room(c.mesh, c.net, options, quiet);
  const TabRoomReport after = describe_tab_room(c.mesh, r.net, options, flat);
  EXPECT_EQ(after.blocked, r.blocked_after);
  EXPECT_LT(3 * after.blocked, before.blocked);  // 215 -> 45 and 182 -> 49 in two nets of seed 1
  EXPECT_LT(3 * after.flat_leaves, before.flat_leaves);
}

// A leaf of the cut tree can have a tab only at a vertex whose fan, opened at the leaf's edge,
// leaves a wide enough wedge: the octahedron's corners (defect 120 degrees) can, an almost flat
// apex (defect 0.02 degrees) cannot at a 0.02 tab (2 mm when printed 200 mm long), but can at a
// much smaller tab (the model printed far larger), and a saddle (negative defect) never can.
TEST(TabClearance, LeafRoomNeedsAWideEnoughDefect) {
  TabClearanceOptions options;
  options.min_height = 0.02;
  const std::vector<char> sharp = leaf_room(test::octahedron(1), options);
  EXPECT_EQ(sharp, std::vector<char>(6, 1));
  const Mesh flat_mesh = test::octahedron(0.01);
  ASSERT_LT(angle_defects(flat_mesh)[4], 0.001);
  const std::vector<char> flat = leaf_room(flat_mesh, options);
  EXPECT_EQ(flat[4], 0);
  for (int v : {0, 1, 2, 3, 5}) EXPECT_EQ(flat[v], 1) << v;
  TabClearanceOptions tiny = options;
  tiny.min_height = 1e-5;
  EXPECT_EQ(leaf_room(flat_mesh, tiny)[4], 1);
  Mesh saddle;  // vertex 0 amid six faces whose rim goes up and down: more than 360 degrees
  saddle.vertices.push_back({0, 0, 0});
  for (int i = 0; i < 6; ++i) {
    const double a = i * std::numbers::pi / 3;
    saddle.vertices.push_back({std::cos(a), std::sin(a), i % 2 ? 0.8 : -0.8});
    saddle.faces.push_back({0, 1 + i, 1 + (i + 1) % 6});
  }
  ASSERT_LT(angle_defects(saddle)[0], 0);
  EXPECT_EQ(leaf_room(saddle, tiny), std::vector<char>(7, 0));
}

// leaf_room is a necessary condition for room, whatever the rest of the net: on the nets of
// two dense meshes, before and after the pass, every leaf of the cut tree at a vertex without
// leaf room has a blocked edge (edges_without_tab_room's own count, against the whole net). A
// tenth of the pass's default budget: any net the pass makes will do.
TEST(TabClearance, LeavesWhereNoLeafCanHaveRoomAreBlocked) {
  for (const char* file : {"sample.obj", "thingi10k_65004.stl"}) {
    const Case c = unfolded(file);
    ASSERT_FALSE(c.mesh.faces.empty()) << file;
    TabClearanceOptions options;
    options.min_height = c.min_height;
    options.max_evaluations = 10'000;
    const double flat = 10 * std::numbers::pi / 180;
    Progress quiet;
    const TabClearanceResult r = clear_tab_room(c.mesh, c.net, options, quiet);
    EXPECT_GT(r.moves, 0u) << file;  // the net after the pass is another net
    for (const Net* net : {&c.net, &r.net}) {
      const TabRoomReport report = describe_tab_room(c.mesh, *net, options, flat);
      EXPECT_GT(report.leaf_room_vertices, 0u) << file;
      EXPECT_EQ(report.interior_vertices + report.boundary_vertices, c.mesh.vertices.size());
      EXPECT_LT(report.leaf_room_vertices, report.interior_vertices / 2) << file;
      EXPECT_LE(report.leaves_without_room, report.leaves) << file;
      EXPECT_EQ(report.leaves_without_room_blocked, report.leaves_without_room) << file;
    }
    const TabRoomReport before = describe_tab_room(c.mesh, c.net, options, flat);
    EXPECT_GT(before.leaves_without_room, 20u) << file;  // the check above has something to check
  }
}

// Compound moves (a hair re-hung: two swaps checked together) are made on a dense net, and the
// net stays a valid, overlap-free single piece whose blocked edges are what the pass says.
TEST(TabClearance, CompoundMovesKeepTheNetValid) {
  const Case c = unfolded("sample.obj");
  ASSERT_FALSE(c.mesh.faces.empty());
  TabClearanceOptions options;
  options.min_height = c.min_height;
  options.max_evaluations = 50'000;
  Progress quiet;
  const TabClearanceResult r = clear_tab_room(c.mesh, c.net, options, quiet);
  EXPECT_GT(r.compound_moves, 0u);
  EXPECT_LE(2 * r.compound_moves, r.moves);
  EXPECT_LT(r.blocked_after, r.blocked_before);
  EXPECT_EQ(edges_without_tab_room(c.mesh, r.net, options).size(), r.blocked_after);
  const NetCheckReport check = check_net(c.mesh, r.net);
  EXPECT_TRUE(check.ok()) << check.summary();
  // Without them: single swaps only.
  options.compound_moves = false;
  const TabClearanceResult single = clear_tab_room(c.mesh, c.net, options, quiet);
  EXPECT_EQ(single.compound_moves, 0u);
  EXPECT_TRUE(check_net(c.mesh, single.net).ok());
}

// Kicks: where the tabu search stops, a swap that opens an edge is made in spite of its
// overlaps, the unfolder's local repair removes them, and a short search from there may beat
// the search's best net (sample.obj's TU net at seed 1: 20 edges without room by the search
// alone, 12 with kicks).
TEST(TabClearance, KicksOpenEdgesTheSearchLeavesBlocked) {
  const Case c = unfolded("sample.obj");
  ASSERT_FALSE(c.mesh.faces.empty());
  TabClearanceOptions options;
  options.min_height = c.min_height;
  Progress quiet;
  options.second_round = false;
  const TabClearanceResult search = clear_tab_room(c.mesh, c.net, options, quiet);
  EXPECT_EQ(search.kicks, 0u);
  EXPECT_LE(search.evaluations, options.max_evaluations);
  options.second_round = true;
  const TabClearanceResult kicked = clear_tab_room(c.mesh, c.net, options, quiet);
  EXPECT_GT(kicked.kicks, 0u);
  EXPECT_LT(kicked.blocked_after, search.blocked_after);
  EXPECT_GT(kicked.moves, search.moves);
  EXPECT_LE(kicked.evaluations, 2 * options.max_evaluations);
  // The kicked net is a valid overlap-free single piece, with the blocked edges it reports.
  EXPECT_EQ(edges_without_tab_room(c.mesh, kicked.net, options).size(), kicked.blocked_after);
  const NetCheckReport check = check_net(c.mesh, kicked.net);
  EXPECT_TRUE(check.ok()) << check.summary();
  // Deterministic, kicks included.
  const TabClearanceResult again = clear_tab_room(c.mesh, c.net, options, quiet);
  EXPECT_EQ(again.net.parent, kicked.net.parent);
  EXPECT_EQ(again.kicks, kicked.kicks);
  EXPECT_EQ(again.evaluations, kicked.evaluations);
  EXPECT_FALSE(kicked.searched_on);
  // A search that spends a small budget with many edges left goes on instead of kicking.
  options.max_evaluations = 5'000;
  options.second_round = false;
  const TabClearanceResult short_search = clear_tab_room(c.mesh, c.net, options, quiet);
  ASSERT_GT(short_search.blocked_after, 64u);
  options.second_round = true;
  const TabClearanceResult searched_on = clear_tab_room(c.mesh, c.net, options, quiet);
  EXPECT_TRUE(searched_on.searched_on);
  EXPECT_EQ(searched_on.kicks, 0u);
  EXPECT_GT(searched_on.evaluations, options.max_evaluations);
  EXPECT_LE(searched_on.evaluations, 2 * options.max_evaluations);
  EXPECT_LT(searched_on.blocked_after, short_search.blocked_after);
  EXPECT_EQ(edges_without_tab_room(c.mesh, searched_on.net, options).size(),
            searched_on.blocked_after);
  EXPECT_TRUE(check_net(c.mesh, searched_on.net).ok());
}

// The showcase: the Stanford bunny (2000 faces) at 200 mm, progressive QQ.
TEST(TabClearance, BunnyAt200mm) {
  const std::filesystem::path file =
      std::filesystem::path(papernet::test::shared_data_dir()) / "bench/2000/draco__bun_zipper.obj";
  if (!std::filesystem::exists(file))
    GTEST_SKIP() << "needs ../shared/data: " << file << " is absent";
  const Mesh mesh = load_mesh_file(file.string()).mesh;
  Progress quiet;
  ProgressiveOptions unfold;
  unfold.tabu.time_limit_seconds = 60;
  const ProgressiveResult r = unfold_progressive(mesh, unfold, quiet);
  ASSERT_TRUE(r.overlap_free);
  Vec3 lo = r.mesh.vertices[0], hi = lo;
  for (const Vec3& v : r.mesh.vertices) {
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  TabClearanceOptions options;
  options.min_height = 2.0 / (200.0 / std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}));
  const TabClearanceResult room = clear_tab_room(r.mesh, r.net, options, quiet);
  EXPECT_GT(room.blocked_before, 100u);
  EXPECT_LT(3 * room.blocked_after, room.blocked_before);  // 247 -> 77 at seed 1
  EXPECT_TRUE(check_net(r.mesh, room.net).ok());
}

TEST(TabClearance, NothingToDoLeavesTheNetAlone) {
  const Mesh cube = test::cube();
  const Net net = test::bfs_net(cube);  // the cube's BFS net does not overlap
  ASSERT_TRUE(check_net(cube, net).ok());
  Progress quiet;
  TabClearanceOptions options;  // min_height 0: every edge has room
  TabClearanceResult r = clear_tab_room(cube, net, options, quiet);
  EXPECT_EQ(r.moves, 0u);
  EXPECT_EQ(r.net.parent, net.parent);
  // Tabs of a tenth of the edge fit everywhere around the cube's net.
  options.min_height = 0.1;
  EXPECT_TRUE(edges_without_tab_room(cube, net, options).empty());
  r = clear_tab_room(cube, net, options, quiet);
  EXPECT_EQ(r.blocked_before, 0u);
  EXPECT_EQ(r.moves, 0u);
  EXPECT_EQ(r.net.parent, net.parent);
}

TEST(TabClearance, TabShapesLieOutsideTheirEdge) {
  const std::array<Vec2, 3> face{Vec2{0, 0}, Vec2{4, 0}, Vec2{1, 3}};
  for (const TabShape& shape : tab_shapes(45)) {
    const auto t = tab_trapezoid(face, 0, shape, 1);
    // Base on the edge y = 0 within [0, 4], top one unit below it (the face is above).
    EXPECT_NEAR(t[0].y, 0, 1e-12);
    EXPECT_NEAR(t[1].y, 0, 1e-12);
    EXPECT_NEAR(t[2].y, -1, 1e-12);
    EXPECT_NEAR(t[3].y, -1, 1e-12);
    EXPECT_GE(std::min(t[0].x, t[1].x), -1e-12);
    EXPECT_LE(std::max(t[0].x, t[1].x), 4 + 1e-12);
    EXPECT_GT(t[0].x - t[1].x, 0.4 * 4 - 1e-9);  // at least 40 % of the edge
    EXPECT_GT(t[3].x, t[2].x);                   // the top keeps some length
  }
  EXPECT_EQ(tab_shapes(45).size(), 36u);
}

}  // namespace
}  // namespace papernet
