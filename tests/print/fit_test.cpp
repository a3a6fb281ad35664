// The fit layout (docs/print.md): pieces cut along folds until each fits a sheet, then nested
// onto sheets. Checked from the drawn pages, not from the layout's own data.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <regex>
#include <set>
#include <sstream>

#include "core/errors.h"
#include "core/mesh/simplify.h"
#include "core/tabs/tab_clearance.h"
#include "core/unfold/net_check.h"
#include "core/unfold/tabu.h"
#include "core/unfold/unfolding.h"
#include "print/arrange.h"
#include "print/fit.h"
#include "print/grow.h"
#include "print/internal/nest_outlines.h"
#include "print/merge.h"
#include "print/nest.h"
#include "print/svg.h"
#include "tests/support/meshes.h"
#include "tests/support/polygons.h"
#include "tests/support/printable.h"
#include "tests/support/sanitized.h"
#include "tests/support/svg.h"

namespace papernet {
namespace {

// The mesh of tests/data called `name`, as test_data_meshes gives it (no faces: there is none).
Mesh data_mesh(const std::string& name) {
  for (auto& [file, mesh] : test::test_data_meshes())
    if (file == name) return mesh;
  return {};
}

struct Unfolded {
  Mesh mesh;
  Net net;
};

Unfolded tabu_net(const std::string& file) {
  for (auto& [name, mesh] : test::test_data_meshes()) {
    if (name != file) continue;
    Progress quiet;
    TabuOptions options;
    options.time_limit_seconds = 600;  // against a hang only: ASan on a loaded machine is slow
    return {mesh, unfold_tabu(mesh, options, quiet).net};
  }
  ADD_FAILURE() << "tests/data has no " << file;
  return {};
}

/// Whether the points fit a room box at some turn: every quarter degree tried, with `slack` mm
/// for the turns between.
bool fits_at_some_turn(const std::vector<Vec2>& points, Vec2 room, double slack) {
  for (int step = 0; step < 4 * 180; ++step) {
    const double a = step * std::numbers::pi / (4 * 180);
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (Vec2 p : points) {
      const double x = std::cos(a) * p.x - std::sin(a) * p.y;
      const double y = std::sin(a) * p.x + std::cos(a) * p.y;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    if (x1 - x0 <= room.x + slack && y1 - y0 <= room.y + slack) return true;
  }
  return false;
}

// A4 with 10 mm margins, less room for 6 mm tabs and 2 mm to cut along.
constexpr Vec2 kRoom{210 - 20 - 14, 297 - 20 - 14};

/// Each part's polygons as nest_outlines placed them (turned, then moved), in millimetres
/// (parts are in micrometres; a polygon's repeated first point dropped), by sheet. Fails the test
/// where a part is unplaced or reaches past a `width` x `height` sheet.
std::map<int, std::vector<std::vector<Vec2>>> placed_polygons(
    const std::vector<print_detail::NestPart>& parts,
    const std::vector<print_detail::NestedOutline>& placed, std::int64_t width,
    std::int64_t height) {
  std::map<int, std::vector<std::vector<Vec2>>> on_sheet;
  EXPECT_EQ(placed.size(), parts.size());
  for (std::size_t i = 0; i < parts.size() && i < placed.size(); ++i) {
    EXPECT_GE(placed[i].sheet, 0) << "part " << i;
    for (const auto& shape : parts[i]) {
      std::vector<Vec2> moved;
      for (const print_detail::IntPoint& p : shape) {
        const Vec2 q =
            rotate(Vec2{static_cast<double>(p.x), static_cast<double>(p.y)}, placed[i].angle) +
            Vec2{static_cast<double>(placed[i].dx), static_cast<double>(placed[i].dy)};
        EXPECT_GE(q.x, -1) << "part " << i;
        EXPECT_GE(q.y, -1) << "part " << i;
        EXPECT_LE(q.x, static_cast<double>(width) + 1.0) << "part " << i;
        EXPECT_LE(q.y, static_cast<double>(height) + 1.0) << "part " << i;
        moved.push_back(1e-3 * q);
      }
      moved.pop_back();  // the repeated first point
      on_sheet[placed[i].sheet].push_back(moved);
    }
  }
  return on_sheet;
}

/// A part: the rectangle from the origin to (x, y), in micrometres.
print_detail::NestPart rectangle(std::int64_t x, std::int64_t y) {
  return {{{0, 0}, {x, 0}, {x, y}, {0, y}, {0, 0}}};
}

/// A part: an L from the origin, `wide` along x and `tall` along y, its two bars `bar` thick (the
/// hollow between them up and to the right), in micrometres.
print_detail::NestPart ell(std::int64_t wide, std::int64_t tall, std::int64_t bar) {
  return {{{0, 0}, {wide, 0}, {wide, bar}, {bar, bar}, {bar, tall}, {0, tall}, {0, 0}}};
}

/// The deepest overlap of two polygons on one sheet, in millimetres (the polygons of one part only
/// touch, as those of two parts must).
double deepest_overlap(const std::map<int, std::vector<std::vector<Vec2>>>& on_sheet) {
  double deepest = 0;
  for (const auto& [sheet, shapes] : on_sheet)
    for (std::size_t i = 0; i < shapes.size(); ++i)
      for (std::size_t j = i + 1; j < shapes.size(); ++j)
        deepest = std::max(deepest, test::overlap_thickness(shapes[i], shapes[j]));
  return deepest;
}

TEST(Fit, CutsALargeNetIntoTreesThatEachFitTheSheet) {
  const Unfolded u = tabu_net("sample.obj");
  ASSERT_FALSE(u.mesh.faces.empty());
  const double scale = print_scale(u.mesh, {});  // 200 mm
  const std::vector<int> one(u.mesh.faces.size(), 0);
  const FitPieces fit = cut_to_fit(u.net, one, scale, {kRoom, {}}, "A4", 200);
  ASSERT_GT(fit.pieces, 1) << "sample.obj at 200 mm is larger than a sheet";
  EXPECT_EQ(fit.cut_links, fit.pieces - 1);
  // Only links were cut: every face keeps its place, each piece is one tree of the old links.
  EXPECT_EQ(fit.net.points, u.net.points);
  std::vector<int> roots(fit.pieces, 0);
  std::vector<std::vector<Vec2>> points(fit.pieces);
  for (std::size_t f = 0; f < u.mesh.faces.size(); ++f) {
    const int p = fit.piece[f];
    ASSERT_GE(p, 0);
    ASSERT_LT(p, fit.pieces);
    if (fit.net.parent[f] < 0) {
      ++roots[p];
    } else {
      EXPECT_EQ(fit.net.parent[f], u.net.parent[f]);
      EXPECT_EQ(fit.piece[fit.net.parent[f]], p) << "face " << f << " hangs from another piece";
    }
    for (Vec2 q : u.net.points[f]) points[p].push_back(scale * q);
  }
  for (int p = 0; p < fit.pieces; ++p) {
    EXPECT_EQ(roots[p], 1) << "piece " << p;
    EXPECT_TRUE(fits_at_some_turn(points[p], kRoom, 1.0)) << "piece " << p;
  }
  const NetCheckReport check = check_pieces(u.mesh, fit.net, fit.piece);
  EXPECT_TRUE(check.ok()) << check.summary();
  // The whole net does not fit, so the cut was needed; a net that fits is left alone.
  std::vector<Vec2> all;
  for (const auto& ps : points) all.insert(all.end(), ps.begin(), ps.end());
  EXPECT_FALSE(fits_at_some_turn(all, kRoom, 0));
  const FitPieces small = cut_to_fit(u.net, one, 0.2 * scale, {kRoom, {}}, "A4", 40);  // 40 mm
  EXPECT_EQ(small.pieces, 1);
  EXPECT_EQ(small.cut_links, 0);
  EXPECT_EQ(small.net.parent, u.net.parent);
}

TEST(Fit, ShrunkPiecesFitTheSmallerBoxAndAFaceLargerThanItIsAPieceAlone) {
  const Unfolded u = tabu_net("sample.obj");
  ASSERT_FALSE(u.mesh.faces.empty());
  const double scale = print_scale(u.mesh, {});  // 200 mm
  const std::vector<int> one(u.mesh.faces.size(), 0);
  const FitPieces full = cut_to_fit(u.net, one, scale, {kRoom, {}}, "A4", 200);
  const FitPieces half = cut_to_fit(u.net, one, scale, {kRoom, {}}, "A4", 200, 0.5);
  EXPECT_GT(half.pieces, full.pieces);
  std::vector<std::vector<Vec2>> points(half.pieces);
  for (std::size_t f = 0; f < u.mesh.faces.size(); ++f)
    for (Vec2 q : u.net.points[f]) points[half.piece[f]].push_back(scale * q);
  for (int p = 0; p < half.pieces; ++p)
    EXPECT_TRUE(fits_at_some_turn(points[p], 0.5 * kRoom, 1.0)) << "piece " << p;
  const NetCheckReport check = check_pieces(u.mesh, half.net, half.piece);
  EXPECT_TRUE(check.ok()) << check.summary();

  // A tetrahedron whose faces fit the room but not a tenth of it: four pieces of one face.
  const Mesh mesh = test::tetrahedron();
  const Net net = test::bfs_net(mesh);
  const std::vector<int> four(mesh.faces.size(), 0);
  double side = 0;
  for (const auto& t : net.points)
    for (int k = 0; k < 3; ++k) side = std::max(side, norm(t[k] - t[(k + 1) % 3]));
  const double big = 0.5 * kRoom.x / side;  // the longest side half the room's width
  const FitPieces alone = cut_to_fit(net, four, big, {kRoom, {}}, "A4", 100, 0.1);
  EXPECT_EQ(alone.pieces, 4);
  EXPECT_EQ(alone.cut_links, 3);
  EXPECT_THROW(cut_to_fit(net, four, 4 * big, {kRoom, {}}, "A4", 400, 0.1), InvalidOptionException);
}

// Every cut is needed: no two pieces on the two sides of a cut link fit the box together (the
// links glued back where they do: cutting the largest subtrees first from the leaves up can cut
// one that fits with what is left once the next is cut). Checked at every turn, the room a
// millimetre smaller (the cut's own test turns the box along the hull's edges only). Cut to
// 0.4 of the room and glued back up to 0.7 of it, the pieces fit 0.7 of the room and are fewer.
TEST(Fit, NoTwoPiecesAcrossACutFitTogether) {
  int cuts = 0;
  for (const std::string file : {"sample.obj", "thingi10k_65004.stl"}) {
    const Unfolded u = tabu_net(file);
    ASSERT_FALSE(u.mesh.faces.empty()) << file;
    const double scale = print_scale(u.mesh, {});  // 200 mm
    const std::vector<int> one(u.mesh.faces.size(), 0);
    int pieces_at_04 = 0;
    for (const auto& [shrink, glue] :
         {std::pair{1.0, 0.0}, {0.7, 0.0}, {0.5, 0.0}, {0.4, 0.0}, {0.4, 0.7}}) {
      const FitPieces fit = cut_to_fit(u.net, one, scale, {kRoom, {}}, "A4", 200, shrink, glue);
      const double box = std::max(shrink, glue);
      EXPECT_TRUE(check_pieces(u.mesh, fit.net, fit.piece).ok()) << file;
      std::vector<std::vector<Vec2>> points(fit.pieces);
      for (std::size_t f = 0; f < u.mesh.faces.size(); ++f)
        for (Vec2 q : u.net.points[f]) points[fit.piece[f]].push_back(scale * q);
      // A face larger than the box is a piece of its own (it fits the room).
      for (int p = 0; p < fit.pieces; ++p)
        EXPECT_TRUE(fits_at_some_turn(points[p], (points[p].size() == 3 ? 1 : box) * kRoom, 1.0))
            << file << " piece " << p;
      for (std::size_t f = 0; f < u.mesh.faces.size(); ++f) {
        if (fit.net.parent[f] >= 0 || u.net.parent[f] < 0) continue;
        ++cuts;
        std::vector<Vec2> both = points[fit.piece[f]];
        const auto& other = points[fit.piece[u.net.parent[f]]];
        both.insert(both.end(), other.begin(), other.end());
        EXPECT_FALSE(fits_at_some_turn(both, box * kRoom, -1))
            << file << " at " << shrink << ", " << glue << ": face " << f
            << " could hang from its parent";
      }
      if (glue == 0 && shrink == 0.4) pieces_at_04 = fit.pieces;
      if (glue > 0) {
        EXPECT_LT(fit.pieces, pieces_at_04) << file;
      }
      std::printf("%s cut to %.1f of the room, glued back to %.1f: %d pieces\n", file.c_str(),
                  shrink, box, fit.pieces);
    }
  }
  EXPECT_GT(cuts, 50);
}

TEST(Fit, AFaceLargerThanTheSheetIsAnErrorNamingItAndTheSizeThatPrints) {
  const Mesh mesh = test::tetrahedron();
  const Net net = test::bfs_net(mesh);
  const std::vector<int> one(mesh.faces.size(), 0);
  try {
    cut_to_fit(net, one, 1000, {kRoom, {}}, "A4", 1000);
    ADD_FAILURE() << "a face of about a metre fitted an A4 sheet";
  } catch (const InvalidOptionException& e) {
    EXPECT_EQ(e.code(), "face_too_large");
    EXPECT_EQ(e.option(), "size_mm");
    const std::string message = e.what();
    EXPECT_TRUE(std::regex_search(message, std::regex("^face [0-3] prints [0-9]+ x [0-9]+ mm")))
        << message;
    EXPECT_NE(message.find("A4"), std::string::npos) << message;
    EXPECT_NE(message.find("263 x 176 mm"), std::string::npos) << message;
    // The largest size it names prints; a little more does not.
    std::smatch at_most;
    ASSERT_TRUE(std::regex_search(message, at_most, std::regex("at most ([0-9]+) mm"))) << message;
    const double largest = std::stod(at_most[1].str());
    EXPECT_GT(largest, 50);
    EXPECT_NO_THROW(cut_to_fit(net, one, largest, {kRoom, {}}, "A4", largest));
    EXPECT_THROW(cut_to_fit(net, one, largest + 2, {kRoom, {}}, "A4", largest + 2),
                 InvalidOptionException);
  }
}

// The whole path of a print: a dense net is cut to fit, laid out with tabs and strips, nested,
// drawn. Each page, as drawn in its SVG, holds its faces, tabs and strips inside the printable
// area, none overlapping another; every face is drawn once (no tiles), and every page says which
// it is.
/// Each piece of `pieces` is a net of its faces (the independent checker) that fits kRoom at some
/// turn at `scale`.
void expect_nets_that_fit(const Mesh& mesh, const FitPieces& pieces, double scale,
                          const std::string& name) {
  const NetCheckReport check = check_pieces(mesh, pieces.net, pieces.piece);
  EXPECT_TRUE(check.ok()) << name << ": " << check.summary();
  std::vector<std::vector<Vec2>> points(pieces.pieces);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (Vec2 q : pieces.net.points[f]) points[pieces.piece[f]].push_back(scale * q);
  for (int p = 0; p < pieces.pieces; ++p)
    EXPECT_TRUE(fits_at_some_turn(points[p], kRoom, 1.0)) << name << ": piece " << p;
}

// Pieces grown from single faces, flattest folds first (print/grow.h, grow_to_fit): each piece
// is a net of its faces (one tree, glued edges that meet, no overlaps: the independent checker)
// and fits the room at some turn; the same mesh grows the same pieces.
TEST(Grow, PiecesAreNetsOfTheirFacesThatEachFitTheSheet) {
  int meshes = 0;
  for (const auto& [name, mesh] : test::test_data_meshes()) {
    if (name != "thingi10k_134617.stl" && name != "trimesh_ADIS16480_600.obj" &&
        name != "mirror.ply" && name != "sample.obj")
      continue;
    ++meshes;
    const double scale = print_scale(mesh, {});  // 200 mm
    const std::vector<int> one(mesh.faces.size(), 0);
    const FitPieces grown = grow_to_fit(mesh, one, scale, {kRoom, {}});
    EXPECT_GT(grown.pieces, 1) << name << " at 200 mm is larger than a sheet";
    EXPECT_LT(grown.pieces, static_cast<int>(mesh.faces.size()) / 4) << name;
    EXPECT_EQ(grown.cut_links, grown.pieces - 1) << name;
    expect_nets_that_fit(mesh, grown, scale, name);
    const FitPieces again = grow_to_fit(mesh, one, scale, {kRoom, {}});
    EXPECT_EQ(again.net.parent, grown.net.parent) << name;
    EXPECT_EQ(again.net.points, grown.net.points) << name;
    std::printf("%s: %zu faces grow into %d pieces\n", name.c_str(), mesh.faces.size(),
                grown.pieces);
  }
  EXPECT_EQ(meshes, 4) << "tests/data lacks a mesh of this test";
}

/// The cut edges inside the pieces of `grown` (both faces in one piece, not glued) where no tab of
/// `options.min_height` fits on either side (core/tabs' edges_without_tab_room, run on each piece
/// as a mesh and net of its own).
std::size_t slits_without_tab_room(const Mesh& mesh, const FitPieces& grown,
                                   const TabClearanceOptions& options) {
  std::size_t count = 0;
  for (int p = 0; p < grown.pieces; ++p) {
    Mesh part;
    Net net;
    std::map<int, int> vertex, face;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      if (grown.piece[f] == p) face.emplace(static_cast<int>(f), static_cast<int>(face.size()));
    for (const auto& [f, local] : face) {
      std::array<int, 3> t{};
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.faces[f][k];
        const auto [it, added] = vertex.emplace(v, static_cast<int>(part.vertices.size()));
        if (added) part.vertices.push_back(mesh.vertices[v]);
        t[k] = it->second;
      }
      part.faces.push_back(t);
      const int parent = grown.net.parent[f];
      net.parent.push_back(parent < 0 ? -1 : face.at(parent));
      net.points.push_back(grown.net.points[f]);
    }
    count += edges_without_tab_room(part, net, options).size();
  }
  return count;
}

// Grown so that every cut inside a piece has room for a tab (grow_to_fit's `tab_height`), no
// piece has a slit without one, as core/tabs finds them; grown as large as they grow, the
// pieces of sample.obj have hundreds (printed as glue strips). The pieces are still nets that
// fit the room; there are more of them.
TEST(Grow, PiecesGrownForTabsLeaveRoomForATabOnEveryCutInside) {
  int meshes = 0;
  for (const auto& [name, mesh] : test::test_data_meshes()) {
    if (name != "sample.obj" && name != "thingi10k_134617.stl") continue;
    ++meshes;
    PrintOptions print;
    const double scale = print_scale(mesh, print);
    const TabClearanceOptions tabs = tab_clearance_options(mesh, print);
    const std::vector<int> one(mesh.faces.size(), 0);
    const FitPieces large = grow_to_fit(mesh, one, scale, {kRoom, {}});
    const FitPieces for_tabs =
        grow_to_fit(mesh, one, scale, {kRoom, {}}, tabs.min_height, tabs.angle_deg);
    expect_nets_that_fit(mesh, for_tabs, scale, name);
    const std::size_t before = slits_without_tab_room(mesh, large, tabs);
    const std::size_t after = slits_without_tab_room(mesh, for_tabs, tabs);
    EXPECT_EQ(after, 0u) << name;
    EXPECT_GE(for_tabs.pieces, large.pieces) << name;
    if (name == "sample.obj") {
      EXPECT_GT(before, 100u);
    }
    std::printf(
        "%s: %d pieces with %zu cuts inside without a tab's room; grown for tabs, %d with "
        "%zu\n",
        name.c_str(), large.pieces, before, for_tabs.pieces, after);
  }
  EXPECT_EQ(meshes, 2) << "tests/data lacks a mesh of this test";
}

// Small pieces left between larger ones grown again face by face (grow_to_fit's
// `regrow_faces`): fewer pieces, still nets that fit the room, each cut inside with room for a
// tab, and the same pieces every time.
TEST(Grow, SmallPiecesGrownAgainFaceByFaceLeaveFewerPieces) {
  int meshes = 0, fewer = 0;
  for (const auto& [name, mesh] : test::test_data_meshes()) {
    if (name != "sample.obj" && name != "thingi10k_65004.stl" &&
        name != "trimesh_ADIS16480_600.obj")
      continue;
    ++meshes;
    PrintOptions print;
    const double scale = print_scale(mesh, print);
    const TabClearanceOptions tabs = tab_clearance_options(mesh, print);
    const std::vector<int> one(mesh.faces.size(), 0);
    const FitPieces grown =
        grow_to_fit(mesh, one, scale, {kRoom, {}}, tabs.min_height, tabs.angle_deg);
    const FitPieces regrown =
        grow_to_fit(mesh, one, scale, {kRoom, {}}, tabs.min_height, tabs.angle_deg, 6);
    expect_nets_that_fit(mesh, regrown, scale, name);
    EXPECT_EQ(slits_without_tab_room(mesh, regrown, tabs), 0u) << name;
    EXPECT_LE(regrown.pieces, grown.pieces) << name;
    fewer += regrown.pieces < grown.pieces;
    const FitPieces again =
        grow_to_fit(mesh, one, scale, {kRoom, {}}, tabs.min_height, tabs.angle_deg, 6);
    EXPECT_EQ(again.net.parent, regrown.net.parent) << name;
    std::printf("%s: %d pieces grown for tabs, %d with the small ones grown again\n", name.c_str(),
                grown.pieces, regrown.pieces);
  }
  EXPECT_EQ(meshes, 3) << "tests/data lacks a mesh of this test";
  EXPECT_GE(fewer, 2);
}

// Pieces merged two at a time, their faces unfolded anew together (print/merge.h, merge_pieces):
// fewer pieces than grown, each still a net of its faces (the independent checker) that fits the
// room, with room for a tab on every cut inside; the same pieces every time. Offered to a `keep`
// that refuses, no merge is made, and no more are offered than the budget allows; one that
// takes only the first leaves one piece fewer.
TEST(Merge, PiecesMergedTwoAtATimeAreFewerNetsThatFitWithRoomForTabs) {
  const std::string name = "thingi10k_65004.stl";
  const Mesh mesh = data_mesh(name);
  ASSERT_FALSE(mesh.faces.empty()) << "tests/data has no " << name;
  const double scale = print_scale(mesh, {});  // 200 mm
  const TabClearanceOptions tabs = tab_clearance_options(mesh, {});
  const std::vector<int> one(mesh.faces.size(), 0);
  const FitPieces grown =
      grow_to_fit(mesh, one, scale, {kRoom, {}}, tabs.min_height, tabs.angle_deg, 6);
  // Less work than the print's merge (print/merge.h): the sanitized builds run this too.
  MergeBudget budget;
  budget.tests = 50'000;
  budget.tab_evaluations = 20'000;
  const auto started = std::chrono::steady_clock::now();
  const FitPieces merged = merge_pieces(mesh, one, grown, scale, {kRoom, {}}, tabs, budget);
  expect_nets_that_fit(mesh, merged, scale, name);
  EXPECT_EQ(slits_without_tab_room(mesh, merged, tabs), 0u);
  EXPECT_LT(merged.pieces, grown.pieces);
  EXPECT_EQ(merged.cut_links, merged.pieces - 1);
  // Again, reporting: the same pieces; its share of the budget used never falls.
  struct Reports : Progress {
    std::vector<ProgressInfo> seen;
    bool cancel = false;
    void report(const ProgressInfo& info) override { seen.push_back(info); }
    bool cancelled() override { return cancel; }
  } reports;
  const FitPieces again =
      merge_pieces(mesh, one, grown, scale, {kRoom, {}}, tabs, budget, {}, &reports);
  EXPECT_EQ(again.net.parent, merged.net.parent);
  EXPECT_EQ(again.piece, merged.piece);
  ASSERT_FALSE(reports.seen.empty());
  for (std::size_t i = 0; i < reports.seen.size(); ++i) {
    EXPECT_EQ(reports.seen[i].phase, "merge");
    EXPECT_GE(reports.seen[i].phase_fraction, i ? reports.seen[i - 1].phase_fraction : 0.0);
    EXPECT_LE(reports.seen[i].phase_fraction, 1.0);
  }
  EXPECT_GT(reports.seen.back().phase_fraction, 0.5);  // it stopped on its budget
  reports.cancel = true;
  EXPECT_THROW(merge_pieces(mesh, one, grown, scale, {kRoom, {}}, tabs, budget, {}, &reports),
               CancelledException);

  // The glued trees alone merge pieces; with no unfolding at all (no splits either), nothing
  // merges.
  MergeBudget only_glued = budget;
  only_glued.tries = 0;
  const FitPieces glued = merge_pieces(mesh, one, grown, scale, {kRoom, {}}, tabs, only_glued);
  expect_nets_that_fit(mesh, glued, scale, name);
  EXPECT_EQ(slits_without_tab_room(mesh, glued, tabs), 0u);
  EXPECT_LT(glued.pieces, grown.pieces);
  only_glued.glued = 0;
  only_glued.split_shares.clear();
  EXPECT_EQ(merge_pieces(mesh, one, grown, scale, {kRoom, {}}, tabs, only_glued).piece,
            grown.piece);

  // Two offers (within the tests of every build: the sanitized builds' floating point finds
  // fewer merges in them than Release's).
  budget.keeps = 2;
  std::size_t offered = 0;
  const FitPieces refused = merge_pieces(mesh, one, grown, scale, {kRoom, {}}, tabs, budget,
                                         [&](const FitPieces& candidate) {
                                           ++offered;
                                           EXPECT_EQ(candidate.pieces, grown.pieces - 1);
                                           return false;
                                         });
  EXPECT_EQ(offered, 2u);
  EXPECT_EQ(refused.piece, grown.piece);
  EXPECT_EQ(refused.net.points, grown.net.points);
  const FitPieces first = merge_pieces(mesh, one, grown, scale, {kRoom, {}}, tabs, budget,
                                       [&](const FitPieces&) { return offered++ == 2; });
  EXPECT_EQ(first.pieces, grown.pieces - 1);
  expect_nets_that_fit(mesh, first, scale, name);
  std::printf(
      "%s: %d pieces grown, %d merged, %d from glued trees alone (%.1f s for all six "
      "merges)\n",
      name.c_str(), grown.pieces, merged.pieces, glued.pieces,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
}

// With a second thread, the pairs after the one offered to `keep` are unfolded while it is
// laid out (print/merge.cpp, Ahead): the same merges are offered, in the same order, and the
// same pieces made as on one thread, also when the budget runs out on the way. Pieces grown for
// half the room merge for the whole. With 20,000 tests (5 offers) unfoldings made ahead are
// used, and two are made again, made ahead with more tests left than the merge had when it came
// to them (counted once by hand; here they come out the same either way: the tests they spent
// were within the fewer); with 100,000, 9 offers.
TEST(Merge, UnfoldingAheadOnASecondThreadOffersTheSameMerges) {
  const std::string name = "thingi10k_134617.stl";
  const Mesh mesh = data_mesh(name);
  ASSERT_FALSE(mesh.faces.empty()) << "tests/data has no " << name;
  const double scale = print_scale(mesh, {});
  const TabClearanceOptions tabs = tab_clearance_options(mesh, {});
  const std::vector<int> one(mesh.faces.size(), 0);
  const FitPieces grown =
      grow_to_fit(mesh, one, scale, {0.5 * kRoom, {}}, tabs.min_height, tabs.angle_deg, 6);
  for (const std::size_t tests : {std::size_t{20'000}, std::size_t{100'000}}) {
    MergeBudget budget;
    budget.tests = tests;
    budget.tab_evaluations = 5'000;
    // Refuses every third offer, and records each.
    const auto merge = [&](int threads, std::vector<std::vector<int>>& offers) {
      return merge_pieces(
          mesh, one, grown, scale, {kRoom, {}}, tabs, budget,
          [&](const FitPieces& candidate) {
            offers.push_back(candidate.piece);
            return offers.size() % 3 != 0;
          },
          nullptr, threads);
    };
    std::vector<std::vector<int>> alone, ahead;
    const FitPieces on_one = merge(1, alone);
    const FitPieces on_two = merge(2, ahead);
    EXPECT_GE(alone.size(), 3u) << tests << " tests";  // one refused at least
    EXPECT_EQ(ahead, alone) << tests << " tests";
    EXPECT_EQ(on_two.piece, on_one.piece) << tests << " tests";
    EXPECT_EQ(on_two.net.parent, on_one.net.parent) << tests << " tests";
    EXPECT_EQ(on_two.net.points, on_one.net.points) << tests << " tests";
    expect_nets_that_fit(mesh, on_two, scale, name);
    std::printf("%s, %zu tests: %d pieces grown, %d merged, %zu merges offered\n", name.c_str(),
                tests, grown.pieces, on_one.pieces, alone.size());
  }
}

// When no pair of pieces merges, a piece is split between two of its neighbours
// (MergeBudget::split_shares). A flat strip 3 units long in three pieces of a unit, at a scale
// where 1.5 units fit the room's length and 2 do not: no two pieces merge, but the middle one
// split between the two ends leaves two pieces, each a net of its faces (the independent
// checker) that fits.
TEST(Merge, APieceSplitBetweenTwoNeighboursLeavesOnePieceFewer) {
  Mesh strip;
  const int columns = 30;  // 0.1 units wide each, 0.2 tall
  for (int i = 0; i <= columns; ++i) {
    strip.vertices.push_back({0.1 * i, 0, 0});
    strip.vertices.push_back({0.1 * i, 0.2, 0});
  }
  FitPieces three;
  for (int i = 0; i < columns; ++i) {
    const int f = static_cast<int>(strip.faces.size());
    strip.faces.push_back({2 * i, 2 * i + 2, 2 * i + 3});
    strip.faces.push_back({2 * i, 2 * i + 3, 2 * i + 1});
    // A chain through each unit: the column's upper face hangs across its left edge from the
    // lower face of the column before (but in the unit's first column), the lower face from it.
    three.net.parent.push_back(f + 1);
    three.net.parent.push_back(i % 10 == 0 ? -1 : f - 2);
    three.piece.insert(three.piece.end(), 2, i / 10);
  }
  for (const auto& face : strip.faces) {
    std::array<Vec2, 3> flat;
    for (int k = 0; k < 3; ++k) flat[k] = {strip.vertices[face[k]].x, strip.vertices[face[k]].y};
    three.net.points.push_back(flat);
  }
  three.pieces = 3;
  three.cut_links = 2;
  const NetCheckReport check = check_pieces(strip, three.net, three.piece);
  ASSERT_TRUE(check.ok()) << check.summary();
  const double scale = kRoom.y / 1.6;  // 2 units are longer than the room's diagonal
  const std::vector<int> one(strip.faces.size(), 0);
  const TabClearanceOptions no_tabs;  // min_height 0: tabs not asked for
  ASSERT_EQ(no_tabs.min_height, 0);
  MergeBudget budget;
  budget.split_shares.clear();
  EXPECT_EQ(merge_pieces(strip, one, three, scale, {kRoom, {}}, no_tabs, budget).pieces, 3);
  budget.split_shares = MergeBudget{}.split_shares;
  const FitPieces two = merge_pieces(strip, one, three, scale, {kRoom, {}}, no_tabs, budget);
  ASSERT_EQ(two.pieces, 2);
  EXPECT_EQ(two.cut_links, 1);
  expect_nets_that_fit(strip, two, scale, "strip");
  // The middle unit went half to each end: the ends are 1.5 units each.
  int left = 0;
  for (std::size_t f = 0; f < strip.faces.size(); ++f) left += two.piece[f] == two.piece[0];
  EXPECT_EQ(left, 30);
}

// The splits on real meshes: never more pieces than the pairs alone leave (the splits start where
// the pairs stop), each still a net of its faces that fits the room with room for a tab on every
// cut inside, the same every time.
TEST(Merge, SplitsLeaveNoMorePiecesThanPairsOnRealMeshes) {
  int meshes = 0;
  for (const auto& [name, mesh] : test::test_data_meshes()) {
    if (name != "sample.obj" && name != "thingi10k_65004.stl") continue;
    ++meshes;
    const double scale = print_scale(mesh, {});  // 200 mm
    const TabClearanceOptions tabs = tab_clearance_options(mesh, {});
    const std::vector<int> one(mesh.faces.size(), 0);
    const FitPieces grown =
        grow_to_fit(mesh, one, scale, {kRoom, {}}, tabs.min_height, tabs.angle_deg, 6);
    MergeBudget budget;  // less work than the print's, and less still sanitized
    budget.tests = test::light_merge(100'000);
    budget.tab_evaluations = 20'000;
    budget.split_shares.clear();
    const FitPieces pairs = merge_pieces(mesh, one, grown, scale, {kRoom, {}}, tabs, budget);
    budget.split_shares = MergeBudget{}.split_shares;
    const FitPieces split = merge_pieces(mesh, one, grown, scale, {kRoom, {}}, tabs, budget);
    expect_nets_that_fit(mesh, split, scale, name);
    EXPECT_EQ(slits_without_tab_room(mesh, split, tabs), 0u) << name;
    EXPECT_EQ(split.cut_links, split.pieces - 1) << name;
    EXPECT_LE(split.pieces, pairs.pieces) << name;
    const FitPieces again = merge_pieces(mesh, one, grown, scale, {kRoom, {}}, tabs, budget);
    EXPECT_EQ(again.piece, split.piece) << name;
    EXPECT_EQ(again.net.parent, split.net.parent) << name;
    std::printf("%s: %d pieces grown, %d merged by pairs, %d with splits\n", name.c_str(),
                grown.pieces, pairs.pieces, split.pieces);
  }
  EXPECT_EQ(meshes, 2) << "tests/data lacks a mesh of this test";
}

// Pairs whose unfolding lies flat but sprawls past the room are made to fit by hanging its
// branches elsewhere (print/internal/compact.h): models collapsed to 400 faces, their Tabu nets
// cut to fit the room (the search's way at 1 and 0.7 of it) and merged, leave fewer pieces than
// the same merge without (MergeBudget::compact_evaluations_per_face 0), each still a net of its
// faces that fits the room, with no more cuts inside without room for a tab than the cut pieces
// had; the same every time.
// (Release only: the sanitized builds' floating point takes other paths, Makefile's
// SANITIZE_SKIP.)
TEST(Merge, UnfoldingsCompactedToFitMergeIntoFewerPieces) {
  const std::vector<std::pair<std::string, double>> cases{{"Duck.glb", 1.0},
                                                          {"thingi10k_134617.stl", 0.7}};
  std::size_t found = 0;
  for (const auto& [name, whole] : test::test_data_meshes())
    for (const auto& [file, shrink] : cases) {
      if (file != name) continue;
      ++found;
      Progress quiet;
      SimplifyTarget target;
      target.faces = 400;
      const std::optional<Mesh> collapsed =
          simplify_mesh(whole, CollapseStrategy::QQ, target, quiet);
      ASSERT_TRUE(collapsed.has_value()) << name;
      const Mesh& mesh = *collapsed;
      const double scale = print_scale(mesh, {});  // 200 mm
      const TabClearanceOptions tabs = tab_clearance_options(mesh, {});
      const std::vector<int> one(mesh.faces.size(), 0);
      TabuOptions options;
      options.time_limit_seconds = 600;  // against a hang only
      const Net net = unfold_tabu(mesh, options, quiet).net;
      const FitPieces cut = cut_to_fit(net, one, scale, {kRoom, {}}, "A4", 200, shrink, 1);
      MergeBudget budget;
      budget.tests = 100'000;
      budget.tab_evaluations = 20'000;
      const FitPieces compacted = merge_pieces(mesh, one, cut, scale, {kRoom, {}}, tabs, budget);
      expect_nets_that_fit(mesh, compacted, scale, name);
      // The cut pieces keep the Tabu net's slits (no tab room pass here); a merge adds none.
      EXPECT_LE(slits_without_tab_room(mesh, compacted, tabs),
                slits_without_tab_room(mesh, cut, tabs))
          << name;
      const FitPieces again = merge_pieces(mesh, one, cut, scale, {kRoom, {}}, tabs, budget);
      EXPECT_EQ(again.piece, compacted.piece) << name;
      EXPECT_EQ(again.net.points, compacted.net.points) << name;
      budget.compact_evaluations_per_face = 0;
      const FitPieces as_unfolded = merge_pieces(mesh, one, cut, scale, {kRoom, {}}, tabs, budget);
      EXPECT_LT(compacted.pieces, as_unfolded.pieces) << name;
      std::printf("%s at 400 faces: %d pieces cut, %d merged, %d merged without compacting\n",
                  name.c_str(), cut.pieces, compacted.pieces, as_unfolded.pieces);
    }
  EXPECT_EQ(found, cases.size()) << "tests/data lacks a mesh of this test";
}

// A piece never takes faces of two parts: an octahedron whose upper and lower halves are given
// as two parts grows apart along the equator, though it would fit the room whole.
TEST(Grow, PartsGrowApart) {
  const Mesh mesh = test::octahedron();
  std::vector<int> part(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    double z = 0;
    for (int v : mesh.faces[f]) z += mesh.vertices[v].z;
    part[f] = z > 0 ? 0 : 1;
  }
  const double scale = 0.1 * kRoom.x;  // 2 units across: a fifth of the room
  const FitPieces apart = grow_to_fit(mesh, part, scale, {kRoom, {}});
  const FitPieces whole =
      grow_to_fit(mesh, std::vector<int>(mesh.faces.size(), 0), scale, {kRoom, {}});
  EXPECT_EQ(whole.pieces, 1);
  EXPECT_EQ(apart.pieces, 2);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (std::size_t g = 0; g < mesh.faces.size(); ++g) {
      if (part[f] != part[g]) {
        EXPECT_NE(apart.piece[f], apart.piece[g]) << f << " " << g;
      }
    }
  EXPECT_TRUE(check_pieces(mesh, apart.net, apart.piece).ok());
  EXPECT_TRUE(check_pieces(mesh, whole.net, whole.piece).ok());
}

// On A4, and on paper six times its size (a plotter's, 1260 x 1782 mm, nested on a grid scaled
// down with it: print/nest.cpp, kMostNestMm) with the model six times as large.
TEST(Fit, DrawnSheetsHoldEveryFaceOnceInsideThePrintableAreaWithoutOverlaps) {
  const Unfolded u = tabu_net("sample.obj");
  ASSERT_FALSE(u.mesh.faces.empty());
  for (const double times : {1.0, 6.0}) {
    SCOPED_TRACE(times == 1 ? "A4" : "1260 x 1782 mm");
    PrintOptions print;
    print.size_mm = 200 * times;
    const double scale = print_scale(u.mesh, print);
    const std::vector<int> one(u.mesh.faces.size(), 0);
    PageOptions page;  // A4, 10 mm margins
    if (times > 1) page.paper = {"1260x1782mm", 1260, 1782};
    const FitPieces fit =
        cut_to_fit(u.net, one, scale, {Vec2{page.paper.width - 34, page.paper.height - 34}, {}},
                   page.paper.name, print.size_mm);
    PrintLayout layout = layout_net(u.mesh, arrange_pieces(fit.net, fit.piece, 20 / scale), print);
    ASSERT_GT(layout.tabs.size(), 0u);
    const PageLayout pages = nest_pages(layout, fit.piece, page, 2);
    EXPECT_TRUE(pages.fitted);
    const std::vector<std::string> svgs = write_page_svgs(layout, pages);
    ASSERT_EQ(svgs.size(), pages.pages.size());
    EXPECT_LE(static_cast<int>(svgs.size()), fit.pieces + 1);
    std::size_t faces = 0, tabs = 0, strips = 0;
    for (std::size_t k = 0; k < svgs.size(); ++k) {
      const std::string& svg = svgs[k];
      const std::string name =
          "page " + std::to_string(k + 1) + " of " + std::to_string(svgs.size());
      EXPECT_NE(svg.find(name), std::string::npos) << name;
      std::vector<std::vector<Vec2>> shapes = test::svg_polygons(test::svg_group(svg, "faces"));
      faces += shapes.size();
      const auto tab_shapes = test::svg_polygons(test::svg_group(svg, "tabs"));
      tabs += tab_shapes.size();
      shapes.insert(shapes.end(), tab_shapes.begin(), tab_shapes.end());
      const auto strip_shapes = test::svg_polygons(test::svg_group(svg, "strips"));
      strips += strip_shapes.size();
      shapes.insert(shapes.end(), strip_shapes.begin(), strip_shapes.end());
      test::expect_on_the_printable_area_apart(shapes, page, name);
    }
    EXPECT_EQ(faces, u.mesh.faces.size());
    EXPECT_EQ(tabs, layout.tabs.size());
    EXPECT_EQ(strips, layout.strips.size());
  }
}

// The grid nester on its own: an L-shaped part (two rectangles, nested as one) leaves a hollow
// that a square fills on the same sheet (a bottom-left placer that slides from the corner cannot
// reach it), no two placed parts overlap or leave the sheet, and a part without area (a piece of
// slivers) still gets a sheet.
// A piece that fits a sheet only turned across it (no edge of its outline along the page) is
// nested so, not refused: a strip 300 mm long on A4 (190 x 277 mm printable).
TEST(Nest, APieceThatFitsOnlyAcrossTheSheetIsTurnedThere) {
  Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {300, 0, 0}, {300, 3, 0}, {0, 3, 0}};
  mesh.faces = {{0, 1, 2}, {0, 2, 3}};
  Net net;
  net.parent = {-1, 0};
  net.points = {{Vec2{0, 0}, Vec2{300, 0}, Vec2{300, 3}}, {Vec2{0, 0}, Vec2{300, 3}, Vec2{0, 3}}};
  PrintOptions print;
  print.size_mm = 300;  // a millimetre per unit
  PrintLayout layout = layout_net(mesh, net, print);
  const PageOptions page;  // A4, 10 mm margins
  PageLayout pages;
  ASSERT_NO_THROW(pages = nest_pages(layout, {0, 0}, page, 2));
  ASSERT_EQ(pages.pages.size(), 1u);
  const std::vector<std::string> svgs = write_page_svgs(layout, pages);
  for (const auto& shape : test::svg_polygons(test::svg_group(svgs.at(0), "faces")))
    for (Vec2 p : shape) {
      EXPECT_GE(p.x, page.margin_mm - 1e-3);
      EXPECT_LE(p.x, page.paper.width - page.margin_mm + 1e-3);
      EXPECT_GE(p.y, page.margin_mm - 1e-3);
      EXPECT_LE(p.y, page.paper.height - page.margin_mm + 1e-3);
    }
}

TEST(Nest, PartsFillHollowsWithoutOverlapsInsideTheSheet) {
  using print_detail::IntPoint;
  constexpr std::int64_t mm = 1000;  // parts are in micrometres
  auto polygon = [](std::vector<IntPoint> p) {
    p.push_back(p.front());
    return p;
  };
  // A4's printable area with 10 mm margins; an L filling its left and bottom 150 mm, and two
  // 100 mm squares: with the L placed, one square fits only in the L's hollow.
  const std::int64_t w = 190 * mm, h = 277 * mm;
  const std::vector<print_detail::NestPart> parts = {
      {polygon({{0, 0}, {185 * mm, 0}, {185 * mm, 150 * mm}, {0, 150 * mm}}),
       polygon({{0, 150 * mm}, {50 * mm, 150 * mm}, {50 * mm, 270 * mm}, {0, 270 * mm}})},
      {polygon({{0, 0}, {100 * mm, 0}, {100 * mm, 100 * mm}, {0, 100 * mm}})},
      {polygon({{0, 0}, {100 * mm, 0}, {100 * mm, 100 * mm}, {0, 100 * mm}})},
      {polygon({{0, 0}, {30 * mm, 30 * mm}}), polygon({{0, 0}, {0, 20 * mm}})},  // no area
  };
  const std::vector<print_detail::NestedOutline> placed =
      print_detail::nest_outlines(parts, 0, w, h);
  ASSERT_EQ(placed.size(), parts.size());
  const auto on_sheet = placed_polygons(parts, placed, w, h);
  EXPECT_EQ(placed[1].sheet, placed[0].sheet) << "the first square goes into the L's hollow";
  EXPECT_LE(deepest_overlap(on_sheet), 1e-6);
}

// Six rectangles on sheets of 100 x 100 mm, each 1 mm short of whole tens (so that their cells
// do not spill into the next ten): largest first, each way of ranking them (area, longest side,
// box) takes 4 sheets; the parts of the last of those sheets placed first, 3 (the whole sheet's
// part alone on one, the others on two; 254 of 300 tens squared).
TEST(Nest, PartsLeftOnTheLastSheetGoFirstWhenThatSavesASheet) {
  using print_detail::IntPoint;
  constexpr std::int64_t mm = 1000;
  const auto tens = [](std::int64_t a, std::int64_t b) {
    return rectangle((10 * a - 1) * mm, (10 * b - 1) * mm);
  };
  const std::vector<print_detail::NestPart> parts = {tens(3, 9),   tens(5, 9), tens(8, 3),
                                                     tens(10, 10), tens(7, 4), tens(5, 6)};
  const std::vector<print_detail::NestedOutline> placed =
      print_detail::nest_outlines(parts, 0, 100 * mm, 100 * mm);
  std::set<int> sheets;
  for (const auto& p : placed) {
    ASSERT_GE(p.sheet, 0);
    sheets.insert(p.sheet);
  }
  EXPECT_EQ(sheets.size(), 3u);
}

// A part is held by the cells it covers, not by their box: a rectangle 99.2 mm long on a sheet
// 100 mm wide covers 200 columns of cells (half a millimetre each), but the box of its outline
// grown to reach every cell it touches spans 201. Held by that box it fitted no sheet's grid and
// took a sheet of its own, and a 10 mm square another.
TEST(Nest, APartFitsTheSheetByTheCellsItCoversNotTheirBox) {
  constexpr std::int64_t mm = 1000;
  const std::vector<print_detail::NestPart> parts = {rectangle(99'200, 40 * mm),
                                                     rectangle(10 * mm, 10 * mm)};
  const std::vector<print_detail::NestedOutline> placed =
      print_detail::nest_outlines(parts, 0, 100 * mm, 100 * mm);
  ASSERT_EQ(placed.size(), 2u);
  EXPECT_EQ(placed[0].sheet, 0);
  EXPECT_EQ(placed[1].sheet, 0);
  EXPECT_LE(deepest_overlap(placed_polygons(parts, placed, 100 * mm, 100 * mm)), 1e-6);
}

// A sheet whose rows each have room only in a slot 24 mm wide and 110 mm tall (a U of 100 x
// 120 mm on a sheet of 102 x 122 mm, which it fits only upright, taking the rest) holds a bar
// 18 mm wide as tall as fits in it, 109 mm, and not one of 115 mm, which goes on a sheet of its
// own (the bars are nested after the U, the larger first). A sheet is passed over at once when
// it has fewer rows in a row with free runs as long as a band of the part's rows needs: were
// those counted short, or the band taller, the 109 mm bar would go on the second sheet too.
TEST(Nest, ABarGoesIntoASlotAsTallAsItAndNoTaller) {
  constexpr std::int64_t mm = 1000;
  const std::int64_t w = 102 * mm, h = 122 * mm;
  const auto box = [](std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1) {
    return std::vector<print_detail::IntPoint>{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}};
  };
  const std::vector<print_detail::NestPart> parts = {
      {box(0, 0, 100 * mm, 10 * mm), box(0, 10 * mm, 38 * mm, 120 * mm),
       box(62 * mm, 10 * mm, 100 * mm, 120 * mm)},
      rectangle(18 * mm, 109 * mm),
      rectangle(18 * mm, 115 * mm)};
  const std::vector<print_detail::NestedOutline> placed =
      print_detail::nest_outlines(parts, 0, w, h);
  ASSERT_EQ(placed.size(), parts.size());
  EXPECT_EQ(placed[0].sheet, 0);
  EXPECT_EQ(placed[1].sheet, 0) << "the 109 mm bar fits the slot";
  EXPECT_EQ(placed[2].sheet, 1) << "the 115 mm bar does not";
  EXPECT_LE(deepest_overlap(placed_polygons(parts, placed, w, h)), 1e-6);
}

// A part turned a quarter is held by its cells turned (the grid maps onto itself under a quarter
// turn about the origin), which must be those of the part as turned and placed: an L 45 mm wide
// and 90 mm tall fits a sheet 100 x 50 mm only lying down, and the three 20 mm squares after it
// fit only into its hollow. Cells turned the other way round leave the hollow where the L lies.
TEST(Nest, APartTurnedAQuarterIsHeldByItsCellsTurned) {
  constexpr std::int64_t mm = 1000;
  const std::int64_t w = 100 * mm, h = 50 * mm;
  const std::vector<print_detail::NestPart> parts = {
      ell(45 * mm, 90 * mm, 15 * mm), rectangle(20 * mm, 20 * mm), rectangle(20 * mm, 20 * mm),
      rectangle(20 * mm, 20 * mm)};
  const std::vector<print_detail::NestedOutline> placed =
      print_detail::nest_outlines(parts, 0, w, h);
  ASSERT_EQ(placed.size(), parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) EXPECT_EQ(placed[i].sheet, 0) << "part " << i;
  EXPECT_NEAR(std::abs(std::sin(placed[0].angle)), 1, 1e-9) << "the L lies down";
  EXPECT_LE(deepest_overlap(placed_polygons(parts, placed, w, h)), 1e-6);
}

// A part turned half round is held by its cells read from the far corner (the grid maps onto
// itself under a half turn about the origin as well), at the place of the part as turned: on a
// sheet 200 x 50 mm an L 85 mm wide (bars 15 mm thick) lies first in the corner, and an L of 50 x
// 30 mm (bars 10 mm) lies lowest and leftmost after it turned half round, its upright bar down
// beside the first L's foot and its foot over it; a bar 60 x 11 mm then lies at the sheet's foot
// just past that upright bar. Cells turned otherwise, or moved, would place the second L over the
// first, or elsewhere, and cells marked past the second L's would push the bar along.
TEST(Nest, APartTurnedHalfRoundIsHeldByItsCellsTurned) {
  constexpr std::int64_t mm = 1000;
  const std::int64_t w = 200 * mm, h = 50 * mm;
  const std::vector<print_detail::NestPart> parts = {
      ell(85 * mm, 45 * mm, 15 * mm), ell(50 * mm, 30 * mm, 10 * mm), rectangle(60 * mm, 11 * mm)};
  const std::vector<print_detail::NestedOutline> placed =
      print_detail::nest_outlines(parts, 0, w, h);
  ASSERT_EQ(placed.size(), parts.size());
  EXPECT_EQ(placed[0].sheet, 0);
  EXPECT_EQ(placed[1].sheet, 0);
  EXPECT_NEAR(std::cos(placed[0].angle), 1, 1e-9) << "the first L lies as it comes";
  EXPECT_NEAR(std::cos(placed[1].angle), -1, 1e-9) << "the second L lies turned half round";
  // Turned, it spans x from dx - 50 mm to dx and y from dy - 30 mm to dy: at the sheet's foot,
  // its upright bar (the last 10 mm of x) just past the first L's 85 mm.
  EXPECT_LT(placed[1].dy - 30 * mm, 1 * mm);
  EXPECT_GE(placed[1].dx - 10 * mm, 85 * mm);
  EXPECT_LT(placed[1].dx - 10 * mm, 87 * mm);
  EXPECT_EQ(placed[2].sheet, 0);
  EXPECT_NEAR(std::cos(placed[2].angle), 1, 1e-9) << "the bar lies as it comes";
  EXPECT_LT(placed[2].dy, 1 * mm);
  EXPECT_GE(placed[2].dx, placed[1].dx);
  EXPECT_LT(placed[2].dx, placed[1].dx + 2 * mm);
  EXPECT_LE(deepest_overlap(placed_polygons(parts, placed, w, h)), 1e-6);
}

// A part lies on the lowest row where it fits, past the rows where no free run is as long as its
// own (a sheet is searched from the foot, a row too narrow passed over up to the next one with
// room: Sheet::next_row): on a sheet 100 x 50 mm, with an L 85 mm wide (bars 15 mm thick) in the
// corner, a bar 80 x 20 mm has no room beside the L's foot (15 mm) and lies right on it.
TEST(Nest, APartLiesOnTheLowestRowWithRoomForIt) {
  constexpr std::int64_t mm = 1000;
  const std::int64_t w = 100 * mm, h = 50 * mm;
  const std::vector<print_detail::NestPart> parts = {ell(85 * mm, 45 * mm, 15 * mm),
                                                     rectangle(80 * mm, 20 * mm)};
  const std::vector<print_detail::NestedOutline> placed =
      print_detail::nest_outlines(parts, 0, w, h);
  ASSERT_EQ(placed.size(), parts.size());
  EXPECT_EQ(placed[0].sheet, 0);
  EXPECT_NEAR(std::cos(placed[0].angle), 1, 1e-9) << "the L lies as it comes";
  EXPECT_EQ(placed[1].sheet, 0);
  EXPECT_NEAR(std::cos(placed[1].angle), 1, 1e-9);
  // The L's foot ends at placed[0].dy + 15 mm; the bar lies within two cells of it (each part's
  // cells reach a fringe past its outline).
  EXPECT_GE(placed[1].dy, placed[0].dy + 15 * mm);
  EXPECT_LE(placed[1].dy, placed[0].dy + 16 * mm);
  EXPECT_LE(deepest_overlap(placed_polygons(parts, placed, w, h)), 1e-6);
}

}  // namespace
}  // namespace papernet
