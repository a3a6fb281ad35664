// Unfolding::repair_locally: local moves of small sides of the unfold tree after overlaps appear.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/load.h"
#include "core/unfold/net_check.h"
#include "core/unfold/progressive.h"
#include "core/unfold/unfolding.h"
#include "tests/support/meshes.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

Mesh load_test_mesh(const char* name) {
  return load_mesh_file(papernet::test::test_data_dir() + "/" + name).mesh;
}

// The state's bookkeeping agrees with a fresh build, and the only faults the independent checker
// finds are overlapping pairs (its tolerance differs slightly from the state's, so its count of
// them may too).
void expect_consistent(const Unfolding& u) {
  const NetCheckReport report = check_net(u.mesh(), u.net());
  EXPECT_EQ(report.failure_count, report.overlapping_pairs) << report.summary();
  EXPECT_EQ(u.overlap_count(), Unfolding(u.mesh(), u.net().parent).overlap_count());
}

TEST(LocalRepair, LowersOverlapsAndKeepsNetsValidOnTestMeshes) {
  std::size_t before_sum = 0, after_sum = 0;
  for (const char* name : {"sample.obj", "reference.obj", "mirror.ply"}) {
    for (std::uint64_t seed : {1, 2}) {
      SCOPED_TRACE(std::string(name) + " seed " + std::to_string(seed));
      Unfolding u = Unfolding::steepest_edge(load_test_mesh(name), seed);
      const std::size_t before = u.overlap_count();
      LocalRepairStats stats;
      const std::size_t after = u.repair_locally({}, &stats);
      EXPECT_EQ(after, u.overlap_count());
      EXPECT_EQ(after, stats.overlaps);
      EXPECT_LE(after, before + stats.sideways * LocalRepairOptions{}.max_rise);
      before_sum += before;
      after_sum += after;
      expect_consistent(u);
      // The Tabu Unfolder carries on from the repaired state.
      if (std::string(name) != "sample.obj") continue;
      Progress quiet;
      TabuOptions options;
      options.time_limit_seconds = 30;
      EXPECT_TRUE(u.resolve_overlaps(options, quiet));
      const NetCheckReport report = check_net(u.mesh(), u.net());
      EXPECT_TRUE(report.ok()) << report.summary();
    }
  }
  EXPECT_LT(after_sum, before_sum) << "local repair removed no overlap on any test mesh";
}

TEST(LocalRepair, ResolvesASaddleOverlap) {
  const Mesh mesh = test::saddle();
  Unfolding u(mesh, test::saddle_path_tree());
  ASSERT_GT(u.overlap_count(), 0u);
  LocalRepairStats stats;
  EXPECT_EQ(u.repair_locally({}, &stats), 0u);
  EXPECT_GE(stats.moves, 1u);
  const NetCheckReport report = check_net(mesh, u.net());
  EXPECT_TRUE(report.ok()) << report.summary();
}

TEST(LocalRepair, SameStateGivesTheSameNet) {
  const Unfolding start = Unfolding::steepest_edge(load_test_mesh("thingi10k_65004.stl"), 4);
  Unfolding a = start, b = start;
  a.repair_locally({});
  b.repair_locally({});
  const Net na = a.net(), nb = b.net();
  EXPECT_EQ(na.parent, nb.parent);
  ASSERT_EQ(na.points.size(), nb.points.size());
  for (std::size_t f = 0; f < na.points.size(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(na.points[f][k] == nb.points[f][k]) << f;
}

// A walk (LocalRepairOptions::seed) draws its sideways moves: the same seed gives the same net,
// other seeds other walks, and each keeps the state consistent and within its rises.
TEST(LocalRepair, WalksDrawTheirSidewaysMovesFromTheSeed) {
  const Unfolding start = Unfolding::steepest_edge(load_test_mesh("thingi10k_65004.stl"), 1);
  ASSERT_GT(start.overlap_count(), 0u);
  std::vector<std::vector<int>> nets;
  std::size_t sideways = 0;
  for (std::uint64_t seed : {7, 8, 9, 10}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    LocalRepairOptions options;
    options.seed = seed;
    options.max_sideways = 1000;
    Unfolding a = start, b = start;
    LocalRepairStats stats;
    const std::size_t after = a.repair_locally(options, &stats);
    b.repair_locally(options);
    EXPECT_EQ(a.net().parent, b.net().parent);
    EXPECT_LE(after, start.overlap_count() + stats.sideways * options.max_rise);
    expect_consistent(a);
    sideways += stats.sideways;
    nets.push_back(a.net().parent);
  }
  EXPECT_GT(sideways, 0u);
  EXPECT_NE(std::count(nets.begin(), nets.end(), nets.front()), 4) << "every seed walked alike";
}

TEST(LocalRepair, TinyBudgetStopsEarly) {
  Unfolding u = Unfolding::steepest_edge(load_test_mesh("thingi10k_65004.stl"), 1);
  ASSERT_GT(u.overlap_count(), 0u);
  LocalRepairOptions options;
  options.max_tests = 1;
  LocalRepairStats stats;
  u.repair_locally(options, &stats);
  EXPECT_LE(stats.moves, 1u);
  expect_consistent(u);
}

// A cut met again in the same round is not evaluated again, only its tests are counted: the
// nets and every count must be those of evaluating it again, also when the test budget ends the
// repair (the budget must run out after the same round).
TEST(LocalRepair, RepeatedCutsGiveTheSameNetAndCounts) {
  const std::string bunny = papernet::test::shared_data_dir() + "/bench/2000/draco__bun_zipper.obj";
  std::vector<Unfolding> starts{Unfolding::steepest_edge(load_test_mesh("thingi10k_65004.stl"), 1),
                                Unfolding::steepest_edge(load_test_mesh("thingi10k_65004.stl"), 4)};
  if (std::filesystem::exists(bunny))
    starts.push_back(Unfolding::steepest_edge(load_mesh_file(bunny).mesh, 1));
  std::size_t budget_ended = 0;
  for (const Unfolding& start : starts) {
    ASSERT_GT(start.overlap_count(), 0u);
    for (std::size_t budget : {300, 1000, 3000, 100000}) {
      SCOPED_TRACE("budget " + std::to_string(budget));
      Unfolding a = start, b = start;
      LocalRepairOptions options;
      options.max_tests = budget;
      LocalRepairStats sa, sb;
      a.repair_locally(options, &sa);
      options.reuse_cuts = false;
      b.repair_locally(options, &sb);
      EXPECT_EQ(sa.tests, sb.tests);
      EXPECT_EQ(sa.evaluations, sb.evaluations);
      EXPECT_EQ(sa.moves, sb.moves);
      EXPECT_EQ(sa.overlaps, sb.overlaps);
      EXPECT_EQ(a.net().parent, b.net().parent);
      if (sa.tests >= budget) ++budget_ended;
    }
  }
  EXPECT_GT(budget_ended, 0u);
}

// Progressive unfolding (which repairs locally after every split) is reproducible.
TEST(LocalRepair, ProgressiveSameSeedGivesTheSameNet) {
  const Mesh input = load_test_mesh("thingi10k_65004.stl");
  ProgressiveOptions options;
  options.tabu.seed = 3;
  options.tabu.time_limit_seconds = 0;  // no time limits: runs must not depend on speed
  options.split_time_limit_seconds = 0;
  Progress quiet;
  const ProgressiveResult a = unfold_progressive(input, options, quiet);
  const ProgressiveResult b = unfold_progressive(input, options, quiet);
  ASSERT_TRUE(a.complete);
  EXPECT_EQ(a.net.parent, b.net.parent);
  ASSERT_EQ(a.net.points.size(), b.net.points.size());
  for (std::size_t f = 0; f < a.net.points.size(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(a.net.points[f][k] == b.net.points[f][k]) << f;
  EXPECT_EQ(a.stats.iterations, b.stats.iterations);
}

}  // namespace
}  // namespace papernet
