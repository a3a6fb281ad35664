#include "core/mesh/simplify.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <string>

#include "core/io/load.h"
#include "core/mesh/hausdorff.h"
#include "core/mesh/thin_faces.h"
#include "core/mesh/validate.h"
#include "tests/support/meshes.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

Mesh cad_part() {
  return load_mesh_file(papernet::test::test_data_dir() + "/thingi10k_65004.stl").mesh;
}

// The rule for short edges, as detail auto sets it: collapse on while more than 1 % of the edges
// are shorter than `length`, moving the surface at most that far.
SimplifyTarget short_edges(double length) {
  SimplifyTarget target;
  target.short_edge = length;
  target.short_edges_allowed = 0.01;
  target.max_distance = length;
  return target;
}

// A CAD part with 24 small through-holes (trimesh ADIS16480, 600 faces).
Mesh holed_part() {
  return load_mesh_file(papernet::test::test_data_dir() + "/trimesh_ADIS16480_600.obj").mesh;
}

// Model units per printed millimetre with the longest side of `part` printed `printed_mm` long.
double unit_per_mm(const Mesh& part, double printed_mm) {
  const Vec3 size = bounding_box(part).size();
  return std::max({size.x, size.y, size.z}) / printed_mm;
}

// detail auto's rule for short edges, small tunnels and thin faces, `mm` model units to the
// printed millimetre: edges of 3 mm, tunnels of 18 mm loops, faces 3 mm high.
SimplifyTarget cad_rule(double mm) {
  SimplifyTarget target = short_edges(3 * mm);
  target.max_tunnel_loop = 18 * mm;
  target.thin_face = 3 * mm;
  return target;
}

TEST(Simplify, ShortEdgesAreCountedOnce) {
  const Mesh m = test::octahedron();  // 12 edges of length sqrt(2)
  EXPECT_EQ(count_short_edges(m, 1.5), 12u);
  EXPECT_EQ(count_short_edges(m, 1.4), 0u);
}

// A CAD part of slivers and small features: kept whole by a face target it already meets, it is
// collapsed on while its edges are short, and its surface stays within the distance asked for.
TEST(Simplify, ShortEdgesAreCollapsedWithinTheDistance) {
  const Mesh part = cad_part();
  const double diagonal = bounding_box_diagonal(part);
  SimplifyTarget target = short_edges(0.01 * diagonal);
  target.faces = part.faces.size();
  const std::size_t short_before = count_short_edges(part, target.short_edge);
  ASSERT_GT(short_before, part.faces.size() / 4);  // what makes the test mean something
  Progress quiet;
  const std::optional<Mesh> simple = simplify_mesh(part, CollapseStrategy::QQ, target, quiet);
  ASSERT_TRUE(simple);
  EXPECT_LT(simple->faces.size(), part.faces.size() / 2);
  EXPECT_LT(count_short_edges(*simple, target.short_edge), short_before / 10);
  EXPECT_LE(hausdorff_distance(part, *simple).distance * diagonal, target.max_distance * 1.01);

  // No room to move the surface: nothing is collapsed.
  target.max_distance = 0;
  EXPECT_FALSE(simplify_mesh(part, CollapseStrategy::QQ, target, quiet));
  // Without the short-edge rule a face target the part meets collapses nothing either.
  target.short_edge = 0;
  EXPECT_FALSE(simplify_mesh(part, CollapseStrategy::QQ, target, quiet));
}

// The short-edge steps stop when their seconds are spent, with the mesh collapsed so far: none
// at all leaves the collapse to the face target alone (a job's time limit bounds them).
TEST(Simplify, ShortEdgeStepsStopWhenTheirSecondsAreSpent) {
  const Mesh part = cad_part();
  const double diagonal = bounding_box_diagonal(part);
  SimplifyTarget target = short_edges(0.01 * diagonal);
  target.faces = 900;
  Progress quiet;
  const std::optional<Mesh> unlimited = simplify_mesh(part, CollapseStrategy::QQ, target, quiet);
  ASSERT_TRUE(unlimited);
  EXPECT_LT(unlimited->faces.size(), 850u);  // the steps ran
  target.seconds = 1e-12;
  const std::optional<Mesh> limited = simplify_mesh(part, CollapseStrategy::QQ, target, quiet);
  ASSERT_TRUE(limited);
  EXPECT_GT(limited->faces.size(), 850u);  // only the collapse to 900 faces
  EXPECT_LE(limited->faces.size(), 900u);
}

// With only a face target, the collapse stops there.
TEST(Simplify, AFaceTargetAloneIsKept) {
  const Mesh part = cad_part();
  SimplifyTarget target;
  target.faces = 900;
  Progress quiet;
  const std::optional<Mesh> simple = simplify_mesh(part, CollapseStrategy::QQ, target, quiet);
  ASSERT_TRUE(simple);
  EXPECT_LE(simple->faces.size(), 900u);
  EXPECT_GT(simple->faces.size(), 850u);
}

// A plate 1 thick (a box of 40 x 20 x 1, no short edge to collapse) becomes one of its large
// sides when thin plates are asked for and 1 is within the distance allowed; not when the
// distance allowed is less, nor when thin plates are not asked for.
TEST(Simplify, AThinPlateBecomesOneSideWithinTheDistance) {
  Mesh plate = test::cube();
  for (Vec3& v : plate.vertices) v = {40 * v.x, 20 * v.y, v.z};
  SimplifyTarget target;
  target.max_distance = 1.5;
  target.thin_plates = true;
  Progress quiet;
  const std::optional<Mesh> side = simplify_mesh(plate, CollapseStrategy::QQ, target, quiet);
  ASSERT_TRUE(side);
  EXPECT_EQ(side->faces.size(), 2u);
  EXPECT_EQ(validate(*side).boundary_loops, 1u);
  target.max_distance = 0.5;
  EXPECT_FALSE(simplify_mesh(plate, CollapseStrategy::QQ, target, quiet));
  target.max_distance = 1.5;
  target.thin_plates = false;
  EXPECT_FALSE(simplify_mesh(plate, CollapseStrategy::QQ, target, quiet));
}

// A CAD part with 24 small through-holes (trimesh ADIS16480) printed 200 mm long: its collapse
// for short edges gets stuck at 380 faces, the holes' rims still short. Plugging the tunnels with
// loops under 18 mm and flipping slivers under 3 mm lets it go on, within the same distance.
TEST(Simplify, SmallTunnelsArePluggedAndSliversFlippedWhenTheCollapseIsStuck) {
  const Mesh part = holed_part();
  const double mm = unit_per_mm(part, 200);
  Progress quiet;
  const std::optional<Mesh> stuck =
      simplify_mesh(part, CollapseStrategy::QQ, short_edges(3 * mm), quiet);
  ASSERT_TRUE(stuck);
  EXPECT_EQ(validate(*stuck).genus, 24);
  const SimplifyTarget target = cad_rule(mm);
  const std::optional<Mesh> simple = simplify_mesh(part, CollapseStrategy::QQ, target, quiet);
  ASSERT_TRUE(simple);
  const ValidationReport report = validate(*simple);
  EXPECT_TRUE(report.unfoldable()) << report.reason();
  EXPECT_LT(report.genus, 10);
  EXPECT_LT(simple->faces.size(), stuck->faces.size() * 4 / 5);
  EXPECT_LT(count_short_edges(*simple, target.short_edge),
            count_short_edges(*stuck, target.short_edge));
  const auto thin = [&](const Mesh& m) {
    int n = 0;
    for (int f = 0; f < static_cast<int>(m.faces.size()); ++f) n += face_height(m, f) < 1 * mm;
    return n;
  };
  EXPECT_LT(thin(*simple), thin(*stuck) / 2);
  EXPECT_LE(hausdorff_distance(part, *simple).distance * bounding_box_diagonal(part),
            target.max_distance * 1.01);
}

// The same part printed 100 mm long, where detail auto also asks for fewer faces (those a person
// builds at that size): no collapse may close a tunnel, so collapsing it to that many faces with
// its 24 holes crushed it (278 faces, 24 mm from the model: its box a heap). Its small tunnels
// are plugged first, on the most collapsed mesh still within the distance, and it keeps its
// shape within about the distance allowed.
TEST(Simplify, ACollapseToFewerFacesThanItsTunnelsNeedPlugsThemFirst) {
  const Mesh part = holed_part();
  SimplifyTarget target = cad_rule(unit_per_mm(part, 100));
  target.faces = 180;
  Progress quiet;
  const std::optional<Mesh> simple = simplify_mesh(part, CollapseStrategy::QQ, target, quiet);
  ASSERT_TRUE(simple);
  const ValidationReport report = validate(*simple);
  EXPECT_TRUE(report.unfoldable()) << report.reason();
  EXPECT_LT(report.genus, 24);
  EXPECT_LE(simple->faces.size(), 200u);
  EXPECT_LE(hausdorff_distance(part, *simple).distance * bounding_box_diagonal(part),
            1.5 * target.max_distance);
}

// Where no collapse in the strategy's order keeps the surface close enough, the short edges are
// collapsed themselves, into their middle or an end, making no sliver: ADIS16480's collapse
// above stopped with 39 edges under 3 mm (at 282 faces) before 2026-11-29, 18 since (at 252),
// its faces no lower than before and its surface within the distance.
TEST(Simplify, ShortEdgesAreCollapsedThemselvesWhereTheStepsStop) {
  const Mesh part = holed_part();
  const double mm = unit_per_mm(part, 200);
  const SimplifyTarget target = cad_rule(mm);
  Progress quiet;
  const std::optional<Mesh> simple = simplify_mesh(part, CollapseStrategy::QQ, target, quiet);
  ASSERT_TRUE(simple);
  EXPECT_TRUE(validate(*simple).unfoldable());
  EXPECT_LE(count_short_edges(*simple, target.short_edge), 25u) << simple->faces.size();
  EXPECT_LT(simple->faces.size(), 270u);
  double lowest = INFINITY;
  for (int f = 0; f < static_cast<int>(simple->faces.size()); ++f)
    lowest = std::min(lowest, face_height(*simple, f));
  EXPECT_GT(lowest, 0.5 * mm);
  EXPECT_LE(hausdorff_distance(part, *simple).distance * bounding_box_diagonal(part),
            target.max_distance * 1.01);
}

// A thin plate prints as its side only when that side lies flat as one layer: the tray bottom
// of ../shared/data/bench/400 (a plate 2.5 mm thick at 200 mm), its short edges collapsed,
// had a side whose rim turned 461 degrees round one vertex, folded over itself (TU searched it
// for 48 s and printed 7 pieces). The result, side or not, has no such vertex.
TEST(Simplify, APlateSideThatFoldsOverItsBorderIsNotPrinted) {
  const std::string file =
      papernet::test::shared_data_dir() + "/bench/400/trimesh__1002_tray_bottom.obj";
  if (!std::ifstream(file)) GTEST_SKIP() << "needs ../shared/data: " << file << " is absent";
  const Mesh part = load_mesh_file(file).mesh;
  const Vec3 size = bounding_box(part).size();
  const double mm = std::max({size.x, size.y, size.z}) / 200;
  SimplifyTarget target = short_edges(3 * mm);
  target.max_tunnel_loop = 18 * mm;
  target.thin_face = 3 * mm;
  target.thin_plates = true;
  Progress quiet;
  const std::optional<Mesh> simple = simplify_mesh(part, CollapseStrategy::QQ, target, quiet);
  ASSERT_TRUE(simple);
  EXPECT_LT(simple->faces.size(), part.faces.size());
  // Each border vertex's face angles, summed.
  std::map<std::pair<int, int>, int> sides;
  for (const auto& t : simple->faces)
    for (int i = 0; i < 3; ++i) ++sides[{t[i], t[(i + 1) % 3]}];
  std::set<int> border;
  for (const auto& [side, n] : sides)
    if (!sides.count({side.second, side.first})) {
      border.insert(side.first);
      border.insert(side.second);
    }
  std::map<int, double> turn;
  for (const auto& t : simple->faces)
    for (int i = 0; i < 3; ++i) {
      const Vec3 u = simple->vertices[t[(i + 1) % 3]] - simple->vertices[t[i]];
      const Vec3 w = simple->vertices[t[(i + 2) % 3]] - simple->vertices[t[i]];
      turn[t[i]] += std::acos(std::clamp(dot(u, w) / (norm(u) * norm(w)), -1.0, 1.0));
    }
  for (const int v : border)
    EXPECT_LE(turn[v], 2 * std::numbers::pi + 1e-6) << "border vertex " << v;
}

}  // namespace
}  // namespace papernet
