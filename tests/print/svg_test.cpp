#include "print/svg.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <regex>

#include "core/errors.h"
#include "core/tabs/tab_clearance.h"
#include "core/unfold/net_check.h"
#include "core/unfold/progressive.h"
#include "core/unfold/unfolding.h"
#include "print/layout.h"
#include "print/tabs.h"
#include "tests/support/meshes.h"
#include "tests/support/polygons.h"
#include "tests/support/sanitized.h"

namespace papernet {
namespace {

using test::boxes_apart;
using test::intersection_area;
using test::near_pairs;
using test::overlap_thickness;
using test::segment_distance;
using test::signed_area;

bool point_in_triangle(Vec2 p, const std::array<Vec2, 3>& t, double tol) {
  for (int k = 0; k < 3; ++k) {
    const Vec2 a = t[k], b = t[(k + 1) % 3];
    if (cross(b - a, p - a) / norm(b - a) < -tol) return false;
  }
  return true;
}

struct NamedNet {
  std::string name;
  Mesh mesh;
  Net net;
};

// Sanitized (make sanitize), where unfolding and the tab clearance pass run 20 times slower,
// the fixture leaves out the meshes of more than 1,000 faces and gives the pass a tenth of its
// budget on nets of more than 900: the same code on smaller nets, so that the run tests the
// build's correctness, not its speed. Release builds (make check) test every mesh and budget.
#ifdef PAPERNET_TEST_SANITIZED
constexpr std::size_t kLargeNetShare = 10;
constexpr std::size_t kMostFaces = 1000;
#else
constexpr std::size_t kLargeNetShare = 1;
constexpr std::size_t kMostFaces = std::numeric_limits<std::size_t>::max();
#endif

/// Nets to check: breadth-first nets (overlapping, crowded) of the cube, octahedron,
/// tetrahedron and every mesh of tests/data, the Tabu Unfolder's overlap-free nets (TU) of the
/// tests/data meshes, and the progressive unfolder's (QQ, SEMP, SEQ) of those under 2000 faces
/// (the Duck's take 10-30 s each). Built once.
const std::vector<NamedNet>& all_nets() {
  static const std::vector<NamedNet> nets = [] {
    std::vector<NamedNet> out;
    auto meshes = test::test_data_meshes();
    std::erase_if(meshes, [](const auto& named) { return named.second.faces.size() > kMostFaces; });
    for (const auto& [name, mesh] : meshes) {
      Progress quiet;
      // A clock limit only against a hang: the Duck's TU net takes ~1 s, but 30 s were not
      // enough under ASan on a loaded machine, and a net stopped short overlaps (CI failed so).
      TabuOptions options;
      options.time_limit_seconds = 600;
      out.push_back({name + " (TU)", mesh, unfold_tabu(mesh, options, quiet).net});
    }
    for (const auto& [name, mesh] : meshes) {
      if (mesh.faces.size() >= 2000) continue;
      for (auto [strategy, tag] :
           {std::pair{CollapseStrategy::QQ, " (QQ)"}, std::pair{CollapseStrategy::SEMP, " (SEMP)"},
            std::pair{CollapseStrategy::SEQ, " (SEQ)"}}) {
        Progress quiet;
        ProgressiveOptions options;
        options.strategy = strategy;
        options.tabu.time_limit_seconds = 600;
        ProgressiveResult r = unfold_progressive(mesh, options, quiet);
        out.push_back({name + tag, std::move(r.mesh), std::move(r.net)});
      }
    }
    meshes.emplace_back("cube", test::cube());
    meshes.emplace_back("octahedron", test::octahedron());
    meshes.emplace_back("tetrahedron", test::tetrahedron());
    for (auto& [name, mesh] : meshes) out.push_back({name + " (BFS)", mesh, test::bfs_net(mesh)});
    return out;
  }();
  return nets;
}

/// True for the nets of all_nets() that are overlap-free (all but the breadth-first ones).
bool unfolded(const std::string& name) { return name.find("(BFS)") == std::string::npos; }

/// The nets of all_nets() as printed at the default 200 mm: the overlap-free ones after the tab
/// clearance pass, the breadth-first ones as they are. Built once.
const std::vector<TabClearanceResult>& all_print_nets() {
  static const std::vector<TabClearanceResult> nets = [] {
    std::vector<TabClearanceResult> out;
    for (const auto& [name, mesh, net] : all_nets()) {
      Progress quiet;
      // The pass as the engine runs it by default (budget 100,000 candidate moves: about
      // 6 s on the Duck, 2-4 s on reference.obj, sample.obj and thingi10k_65004.stl, less on
      // the others) on the TU nets; on the progressive ones a fifth of it, so that the test
      // stays fast. Sanitized, where the pass runs 20 times slower, the nets of more than 900
      // faces get a tenth of that (kLargeNetShare, above).
      TabClearanceOptions options;
      options.min_height = PrintOptions{}.min_tab_height_mm / print_scale(mesh, {});
      if (name.find("(TU)") == std::string::npos) options.max_evaluations = 20'000;
      if (mesh.faces.size() > 900) options.max_evaluations /= kLargeNetShare;
      TabClearanceResult as_is;  // no net to make room on: the net as it is
      as_is.net = net;
      out.push_back(unfolded(name) ? clear_tab_room(mesh, net, options, quiet) : as_is);
    }
    return out;
  }();
  return nets;
}

/// The default print layout (200 mm, tabs auto) of every net of all_print_nets(), built once.
const std::vector<PrintLayout>& all_layouts() {
  static const std::vector<PrintLayout> layouts = [] {
    std::vector<PrintLayout> out;
    for (std::size_t n = 0; n < all_nets().size(); ++n)
      out.push_back(layout_net(all_nets()[n].mesh, all_print_nets()[n].net, {}));
    return out;
  }();
  return layouts;
}

/// Height of a tab above its base.
double tab_height(const Tab& t) {
  const Vec2 e = t.corners[0] - t.corners[1];
  return std::max(std::abs(cross(e, t.corners[2] - t.corners[1])),
                  std::abs(cross(e, t.corners[3] - t.corners[1]))) /
         norm(e);
}

/// Every cut side of the layout is drawn as cut (or as a tab's hinge) along its whole length.
void expect_cut_sides_covered(const PrintLayout& layout, const std::string& name) {
  std::vector<Segment> lines = layout.cut;
  lines.insert(lines.end(), layout.mountain.begin(), layout.mountain.end());
  for (const NetEdge& e : layout.edges) {
    if (e.kind != EdgeKind::Cut) continue;
    for (EdgeSide s : {e.a, e.b}) {
      if (s.face < 0) continue;
      const Vec2 p0 = layout.faces[s.face][s.k], p1 = layout.faces[s.face][(s.k + 1) % 3];
      const double len = norm(p1 - p0);
      auto on_side = [&](Vec2 q) {
        const double t = dot(q - p0, p1 - p0) / (len * len);
        return std::abs(cross(p1 - p0, q - p0)) / len < 1e-9 && t > -1e-9 && t < 1 + 1e-9;
      };
      double covered = 0;
      for (const Segment& l : lines)
        if (on_side(l.a) && on_side(l.b)) covered += norm(l.b - l.a);
      ASSERT_GE(covered, len - 1e-9) << name << ": a cut side is not cut along all its length";
    }
  }
}

TEST(Tabs, ConvexOverlapIgnoresTouchingAndSeesCrossing) {
  const std::vector<Vec2> a = {{0, 0}, {1, 0}, {0, 1}}, b = {{1, 0}, {0, 1}, {1, 1}};
  EXPECT_FALSE(convex_overlap(a, b, 1e-9));  // share an edge
  const std::vector<Vec2> c = {{0.4, 0.4}, {2, 0.4}, {2, 2}};
  EXPECT_TRUE(convex_overlap(a, c, 1e-9));
  const std::vector<Vec2> d = {{1, 1}, {2, 1}, {2, 2}};
  EXPECT_FALSE(convex_overlap(a, d, 1e-9));  // disjoint
  // The independent clipping check measures what it should.
  EXPECT_NEAR(intersection_area(a, c), 0.01, 1e-12);  // corners (.4,.4) (.6,.4) (.5,.5)
  EXPECT_NEAR(intersection_area(a, b), 0, 1e-12);
}

// The grid of tabs and faces (print/tabs.h) lists a polygon only in the cells it meets and
// skips polygons whose boxes are apart: on long slanted slivers across many cells (a Twin
// plate's faces) and small tabs around them, it answers as testing every stored polygon does.
TEST(Tabs, PolygonGridAnswersAsTestingEveryPolygon) {
  std::vector<std::vector<Vec2>> stored;
  for (int i = 0; i < 40; ++i) {  // slivers 30 to 70 cells long, at every slant
    const double a = 0.157 * i, len = 30 + i;
    const Vec2 p{0.37 * i, -0.21 * i}, u{std::cos(a), std::sin(a)}, n{-u.y, u.x};
    stored.push_back({p, p + len * u, p + len * u + 0.05 * n});
  }
  PolygonGrid grid(1);
  for (const auto& poly : stored) grid.add(poly);
  int hits = 0;
  for (int x = -50; x <= 50; ++x)
    for (int y = -50; y <= 50; ++y) {
      const Vec2 p{0.5 * x + 0.13, 0.5 * y + 0.29};
      const std::vector<Vec2> tab = {p, p + Vec2{0.4, 0.05}, p + Vec2{0.3, 0.3},
                                     p + Vec2{0.05, 0.35}};
      bool any = false;
      for (const auto& poly : stored) any = any || convex_overlap(tab, poly, 1e-9);
      ASSERT_EQ(grid.overlaps(tab, 1e-9), any) << "a tab at " << p.x << ", " << p.y;
      hits += any;
    }
  EXPECT_GT(hits, 100) << "the tabs should meet the slivers often";
}

// A face side marked `prefer` (print/layout.cpp marks the sides whose face holds its label only
// under 1.5 mm) takes its edge's tab when a tab tall enough fits there, although the other side
// has room for a larger one; where it has none, the larger tab wins as before.
TEST(Tabs, APreferredSideTakesTheTabWhenOneTallEnoughFits) {
  // Cut edge 0: side a on a large triangle (its side 0, from (0,0) to (20,0)), side b on a sliver
  // 1 mm wide laid apart (its side 0 the same edge, running the other way).
  std::vector<std::array<Vec2, 3>> faces = {{Vec2{0, 0}, Vec2{20, 0}, Vec2{10, 15}},
                                            {Vec2{20, 40}, Vec2{0, 40}, Vec2{10, 39}}};
  NetEdge edge;
  edge.a = {0, 0};
  edge.b = {1, 0};
  edge.cut_index = 0;
  const std::vector<NetEdge> edges = {edge};
  TabOptions options;
  const TabPlacement plain = place_tabs(faces, edges, options);
  ASSERT_EQ(plain.tabs.size(), 1u);
  EXPECT_EQ(plain.tabs[0].side.face, 0);  // side a first, and a full tab there ends the search
  options.prefer.assign(3 * faces.size(), 0);
  options.prefer[3 * 1 + 0] = 1;
  const TabPlacement preferred = place_tabs(faces, edges, options);
  ASSERT_EQ(preferred.tabs.size(), 1u);
  EXPECT_EQ(preferred.tabs[0].side.face, 1);
  // A face 1.5 mm beyond the sliver's edge leaves it room for tabs under 1.5 mm only: the large
  // triangle's full tab wins.
  faces.push_back({Vec2{-5, 41.5}, Vec2{25, 41.5}, Vec2{10, 50}});
  const TabPlacement blocked = place_tabs(faces, edges, options);
  ASSERT_EQ(blocked.tabs.size(), 1u);
  EXPECT_EQ(blocked.tabs[0].side.face, 0);
}

/// The rectangle of a strip grown by `d` on every side.
std::vector<Vec2> grown(const GlueStrip& strip, double d) {
  const auto& c = strip.corners;
  const Vec2 u = (1 / norm(c[1] - c[0])) * (c[1] - c[0]),
             v = (1 / norm(c[3] - c[0])) * (c[3] - c[0]);
  return {c[0] - d * u - d * v, c[1] + d * u - d * v, c[2] + d * u + d * v, c[3] - d * u + d * v};
}

// The tab clearance pass (core/tab_clearance.h) before printing: it never makes things worse,
// its nets pass the net checker, the layout's strips are (about) its edges without room, and
// on the nets where it opens every near-slit each cut edge gets exactly one tab and no strip.
void expect_clearance_pass_makes_room() {
  std::size_t before = 0, after = 0, nets_without_strips = 0;  // over the unfolders' nets
  for (std::size_t n = 0; n < all_nets().size(); ++n) {
    const auto& [name, mesh, net] = all_nets()[n];
    if (!unfolded(name)) continue;
    const TabClearanceResult& room = all_print_nets()[n];
    const PrintLayout& layout = all_layouts()[n];
    EXPECT_LE(room.blocked_after, room.blocked_before) << name;
    EXPECT_EQ(room.moves == 0, room.blocked_after == room.blocked_before) << name;
    before += room.blocked_before;
    after += room.blocked_after;
    if (room.moves > 0) {
      const NetCheckReport check = check_net(mesh, room.net);
      EXPECT_TRUE(check.ok()) << name << ": " << check.summary();
    }
    // Edges without room get strips; the others get tabs (a few lose their room to
    // neighbours' tabs: 5-11 of the Duck's 2106, by its net), so a net where the pass opened
    // every near-slit has no strip.
    EXPECT_GE(layout.strips.size(), room.blocked_after) << name;
    EXPECT_LE(layout.strips.size(), room.blocked_after + 3 + room.blocked_after / 20) << name;
    if (room.blocked_after == 0) {
      EXPECT_TRUE(layout.strips.empty()) << name << ": " << layout.strips.size() << " strips";
      EXPECT_EQ(layout.tabs.size(), static_cast<std::size_t>(layout.cut_edges)) << name;
      ++nets_without_strips;
    }
    std::printf("%s: %zu -> %zu cut edges without tab room (%zu moves), %zu tabs, %zu strips\n",
                name.c_str(), room.blocked_before, room.blocked_after, room.moves,
                layout.tabs.size(), layout.strips.size());
  }
  // With the test's budgets 30 % of the blocked edges remain (37 % without the pass's second
  // round, its kicks or more search: 3,937 -> 1,179 against 1,445 at de12866).
  if (kLargeNetShare == 1) {
    EXPECT_LT(3 * after, before) << "the pass should open most near-slits";
  }
  std::printf("all nets: %zu -> %zu cut edges without tab room\n", before, after);
  // Meshes where the pass reaches exactly one tab per cut edge and no strip (figures in
  // docs/tabs.md). Which single net keeps a last blocked edge moves with every change to the
  // unfolders (their nets are chaotic in the search's order), so the crowded two are asserted
  // per mesh: at most one strip left on any of their nets, none on three of the four (test
  // budget for the progressive nets: a fifth of the default; all four since the kicks).
  // Box_Draco.glb and mirror.ply: none on every net.
  const auto& nets = all_nets();
  for (const std::string mesh :
       {"Box_Draco.glb", "mirror.ply", "testplate.glb", "thingi10k_134617.stl"}) {
    std::size_t nets_of_mesh = 0, strip_free = 0;
    for (std::size_t n = 0; n < nets.size(); ++n) {
      if (nets[n].name.rfind(mesh + " (", 0) != 0 || !unfolded(nets[n].name)) continue;
      ++nets_of_mesh;
      const PrintLayout& layout = all_layouts()[n];
      EXPECT_LE(all_print_nets()[n].blocked_after, 1u) << nets[n].name;
      EXPECT_LE(layout.strips.size(), 1u) << nets[n].name;
      if (layout.strips.empty() && layout.tabs.size() == static_cast<std::size_t>(layout.cut_edges))
        ++strip_free;
    }
    EXPECT_EQ(nets_of_mesh, 4u) << mesh;  // TU, QQ, SEMP, SEQ
    const bool crowded = mesh == "testplate.glb" || mesh == "thingi10k_134617.stl";
    EXPECT_GE(strip_free, crowded ? 3u : 4u) << mesh;
  }
  EXPECT_GE(nets_without_strips, 15u);  // 16 since the kicks
}

TEST(Tabs, EveryCutEdgeGetsOneTabOrStripAndNothingOverlaps) {
  ASSERT_GE(all_nets().size(), 40u);
  for (std::size_t n = 0; n < all_nets().size(); ++n) {
    const std::string& name = all_nets()[n].name;
    const PrintLayout& layout = all_layouts()[n];
    expect_cut_sides_covered(layout, name);
    EXPECT_TRUE(layout.omitted_tabs.empty())
        << name << ": " << layout.omitted_tabs.size() << " cut edges without glue";
    // Overlaps thinner than 10 nm are touching (the placer's tolerance is a 1 nm depth).
    const double tol = 1e-5;
    std::vector<std::vector<Vec2>> faces, tabs, strips;
    for (const auto& f : layout.faces) faces.push_back({f.begin(), f.end()});
    for (const Tab& t : layout.tabs) tabs.push_back({t.corners.begin(), t.corners.end()});
    for (const GlueStrip& t : layout.strips) strips.push_back({t.corners.begin(), t.corners.end()});
    // Pairs checked where their boxes meet (near_pairs); the first few overlaps are named.
    std::vector<std::string> overlaps;
    auto check = [&](const std::vector<std::vector<Vec2>>& a, const char* what_a,
                     const std::vector<std::vector<Vec2>>& b, const char* what_b, bool same) {
      near_pairs(a, b, 0, [&](std::size_t i, std::size_t j) {
        if ((same && j <= i) || overlaps.size() >= 5) return;
        if (overlap_thickness(a[i], b[j]) > tol)
          overlaps.push_back(std::string(what_a) + " " + std::to_string(i) + " overlaps " + what_b +
                             " " + std::to_string(j));
      });
    };
    for (std::size_t t = 0; t < tabs.size(); ++t)
      EXPECT_GT(signed_area(tabs[t]), 0) << name << " tab " << t;
    check(tabs, "tab", faces, "face", false);
    check(tabs, "tab", tabs, "tab", true);
    // Strips keep a millimetre of free paper around them (0.5 mm checked) so they can be cut.
    std::vector<std::vector<Vec2>> around;
    for (std::size_t t = 0; t < strips.size(); ++t) {
      EXPECT_GT(signed_area(strips[t]), 0) << name << " strip " << t;
      around.push_back(grown(layout.strips[t], 0.5));
      for (Vec2 p : strips[t]) {
        EXPECT_GE(std::min(p.x, p.y), -1e-9) << name << ": strip outside the layout";
        EXPECT_LE(p.x, layout.size.x + 1e-9) << name;
        EXPECT_LE(p.y, layout.size.y + 1e-9) << name;
      }
    }
    check(around, "the 0.5 mm around strip", faces, "face", false);
    check(around, "the 0.5 mm around strip", tabs, "tab", false);
    check(around, "the 0.5 mm around strip", strips, "strip", true);
    for (std::size_t k = 0; k < overlaps.size(); ++k) ADD_FAILURE() << name << ": " << overlaps[k];
    std::map<int, int> glue_per_edge;
    double lowest = std::numeric_limits<double>::infinity();
    std::size_t low = 0;
    for (const Tab& tab : layout.tabs) {
      ++glue_per_edge[tab.edge];
      const NetEdge& e = layout.edges[tab.edge];
      ASSERT_GE(e.cut_index, 0) << name;
      const bool on_a = tab.side.face == e.a.face && tab.side.k == e.a.k;
      const bool on_b = tab.side.face == e.b.face && tab.side.k == e.b.k;
      EXPECT_TRUE(on_a || on_b) << name;
      // The tab's base lies on the side it hangs from and covers at least 40 % of it; it is at
      // least 2 mm tall, or half the edge on edges shorter than 4 mm, and at most 6 mm.
      const auto& tri = layout.faces[tab.side.face];
      const Vec2 e0 = tri[tab.side.k], e1 = tri[(tab.side.k + 1) % 3];
      const double len = norm(e1 - e0);
      for (Vec2 c : {tab.corners[0], tab.corners[1]}) {
        EXPECT_NEAR(cross(e1 - e0, c - e0) / len, 0, 1e-9) << name;
        EXPECT_GE(dot(c - e0, e1 - e0) / len, -1e-9) << name;
        EXPECT_LE(dot(c - e0, e1 - e0) / len, len + 1e-9) << name;
      }
      EXPECT_GE(norm(tab.corners[0] - tab.corners[1]), 0.4 * len - 1e-9) << name;
      const double h = tab_height(tab);
      EXPECT_GE(h, std::min(2.0, 0.5 * len) - 1e-9) << name << ": tab too low to print";
      EXPECT_LE(h, std::max(std::min(6.0, 0.5 * len), std::min(2.0, 0.5 * len)) + 1e-9) << name;
      lowest = std::min(lowest, h);
      low += h < 2;
    }
    std::map<int, const Label*> label_of;
    for (const Label& l : layout.labels) label_of[l.edge] = &l;
    for (const GlueStrip& strip : layout.strips) {
      ++glue_per_edge[strip.edge];
      const NetEdge& e = layout.edges[strip.edge];
      ASSERT_GE(e.cut_index, 0) << name;
      // As long as its edge, at least 4 mm wide, carrying the edge's label.
      const auto& tri = layout.faces[e.a.face];
      const double len = norm(tri[(e.a.k + 1) % 3] - tri[e.a.k]);
      EXPECT_GE(norm(strip.corners[1] - strip.corners[0]), len - 1e-9) << name;
      EXPECT_GE(norm(strip.corners[3] - strip.corners[0]), 4 - 1e-9) << name;
      EXPECT_NEAR(
          cross(strip.corners[1] - strip.corners[0], strip.corners[3] - strip.corners[0]),
          norm(strip.corners[1] - strip.corners[0]) * norm(strip.corners[3] - strip.corners[0]),
          1e-6)
          << name << ": a strip is a rectangle";
      ASSERT_TRUE(label_of.count(strip.edge)) << name;
      EXPECT_EQ(strip.text, label_of[strip.edge]->text) << name;
      EXPECT_GT(strip.text_size, 0) << name;
    }
    int cut_edges = 0;
    for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
      const NetEdge& edge = layout.edges[e];
      if (edge.cut_index < 0) {
        EXPECT_EQ(glue_per_edge.count(e), 0u) << name << ": glue on a fold or boundary";
        continue;
      }
      ++cut_edges;
      EXPECT_EQ(glue_per_edge[e], 1) << name << ": cut edge " << e << " needs one tab or strip";
      // A cut edge never has its two sides on each other: those are folds.
      const auto& fa = layout.faces[edge.a.face];
      const auto& fb = layout.faces[edge.b.face];
      const Vec2 a0 = fa[edge.a.k], a1 = fa[(edge.a.k + 1) % 3];
      const Vec2 b0 = fb[edge.b.k], b1 = fb[(edge.b.k + 1) % 3];
      EXPECT_GT(std::max(norm(a0 - b1), norm(a1 - b0)), 1e-6 * norm(a1 - a0))
          << name << ": cut edge " << e << " has coincident sides";
    }
    EXPECT_EQ(cut_edges, layout.cut_edges);
    EXPECT_EQ(layout.tabs.size() + layout.strips.size(), std::size_t(cut_edges)) << name;
    EXPECT_GT(cut_edges, 0) << name;
    std::printf(
        "%s: %zu faces, %d cut edges, %zu tabs (lowest %.2f mm, %zu under 2 mm), "
        "%zu strips, %zu omitted\n",
        name.c_str(), layout.faces.size(), cut_edges, layout.tabs.size(),
        layout.tabs.empty() ? 0.0 : lowest, low, layout.strips.size(), layout.omitted_tabs.size());
  }
  expect_clearance_pass_makes_room();
}

TEST(Tabs, ModesAndMinimumHeight) {
  const auto& nets = all_nets();
  const auto it = std::find_if(nets.begin(), nets.end(),
                               [](const NamedNet& n) { return n.name == "sample.obj (TU)"; });
  ASSERT_NE(it, nets.end());
  const std::string& name = it->name;
  const Mesh& mesh = it->mesh;
  const std::size_t index = static_cast<std::size_t>(it - nets.begin());
  const Net& net = all_print_nets()[index].net;  // the printed net
  const PrintLayout& any = all_layouts()[index];
  // This dense net needs both: tabs where there is room, strips where there is none.
  EXPECT_GT(any.tabs.size(), 0u) << name;
  EXPECT_GT(any.strips.size(), 0u) << name;
  PrintOptions options;
  options.min_tab_height_mm = 3;
  const PrintLayout tall = layout_net(mesh, net, options);
  for (const Tab& t : tall.tabs) {
    const double len = norm(t.corners[0] - t.corners[1]);  // base: at most the edge
    EXPECT_GE(tab_height(t), std::min(3.0, 0.5 * len) - 1e-9) << name;
  }
  EXPECT_TRUE(tall.omitted_tabs.empty());
  EXPECT_EQ(tall.tabs.size() + tall.strips.size(), static_cast<std::size_t>(tall.cut_edges));
  EXPECT_GT(tall.strips.size(), any.strips.size()) << name;

  options = {};
  options.tabs = TabMode::Strips;
  const PrintLayout strips = layout_net(mesh, net, options);
  EXPECT_TRUE(strips.tabs.empty());
  EXPECT_EQ(strips.strips.size(), static_cast<std::size_t>(strips.cut_edges));
  options.tabs = TabMode::None;
  const PrintLayout none = layout_net(mesh, net, options);
  EXPECT_TRUE(none.tabs.empty() && none.strips.empty());
  EXPECT_EQ(none.omitted_tabs.size(), static_cast<std::size_t>(none.cut_edges));
  options.tabs = TabMode::Auto;
  options.tab_height_mm = 0;  // the old way to switch tabs off
  EXPECT_EQ(layout_net(mesh, net, options).omitted_tabs.size(),
            static_cast<std::size_t>(none.cut_edges));

  // When the pass runs (engine/pipeline.cpp; tests/engine/pipeline_test.cpp runs it).
  options = {};
  EXPECT_TRUE(makes_tab_room(options));
  options.tabs = TabMode::Strips;
  EXPECT_FALSE(makes_tab_room(options));
  options.tabs = TabMode::Auto;
  options.tab_room_budget = 0;
  EXPECT_FALSE(makes_tab_room(options));
  options.tab_room_budget = 1;
  options.tab_height_mm = 0;
  EXPECT_FALSE(makes_tab_room(options));

  EXPECT_EQ(tab_mode_name(TabMode::None), "none");
  PrintOptions bad;
  bad.min_tab_height_mm = -1;
  try {
    bad.validate();
    ADD_FAILURE() << "a negative tab height passed";
  } catch (const InvalidOptionException& e) {
    EXPECT_EQ(e.option(), "min_tab_height_mm");
  }
}

bool inside_face(const Label& l, const std::array<Vec2, 3>& tri) {
  for (Vec2 p : label_box(l))
    if (!point_in_triangle(p, tri, 1e-9)) return false;
  return true;
}

// True when segments ab and cd cross at a point inside both.
bool segments_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return d1 * d2 < 0 && d3 * d4 < 0;
}

bool point_in_quad(Vec2 p, const std::array<Vec2, 4>& q) {
  return point_in_triangle(p, {q[0], q[1], q[2]}, 1e-9) ||
         point_in_triangle(p, {q[0], q[2], q[3]}, 1e-9);
}

// Labels sit inside their face where it holds them at 1.5 mm or more; the rest move where they
// print that large, clear of every other label.
TEST(Labels, TwoMatchingLabelsPerCutEdgeInsideTheirFaces) {
  for (std::size_t n = 0; n < all_nets().size(); ++n) {
    const std::string& name = all_nets()[n].name;
    const PrintLayout& layout = all_layouts()[n];
    std::map<int, std::vector<const Label*>> by_edge;
    for (const Label& l : layout.labels) by_edge[l.edge].push_back(&l);
    EXPECT_EQ(static_cast<int>(by_edge.size()), layout.cut_edges) << name;
    std::map<std::string, int> texts;
    std::size_t far = 0;  // labels with a leader line
    for (const auto& [e, labels] : by_edge) {
      ASSERT_EQ(labels.size(), 2u) << name << " edge " << e;
      EXPECT_EQ(labels[0]->text, labels[1]->text);
      // The edge's number, with a dot where it would read as another number upside down.
      const std::string number = std::to_string(layout.edges[e].cut_index + 1);
      EXPECT_TRUE(labels[0]->text == number || labels[0]->text == number + ".");
      if (number == "6" || number == "9" || number == "16" || number == "91") {
        EXPECT_EQ(labels[0]->text, number + ".");
      }
      if (number == "7" || number == "11" || number == "69") {
        EXPECT_EQ(labels[0]->text, number);
      }
      EXPECT_NE(labels[0]->side.face, labels[1]->side.face);
      ++texts[labels[0]->text];
      for (const Label* l : labels) {
        EXPECT_GT(l->size, 0);
        const auto& tri = layout.faces[l->side.face];
        const auto box = label_box(*l);
        const Vec2 a = tri[l->side.k], b = tri[(l->side.k + 1) % 3], c = tri[(l->side.k + 2) % 3];
        // Away from its edge, with a leader line from its box to its edge, straight or of
        // lines joined end to end (docs/print.md, "Labels").
        const bool led =
            std::any_of(layout.leaders.begin(), layout.leaders.end(), [&](const Segment& s) {
              double to_box = INFINITY;
              for (int k = 0; k < 4; ++k)
                to_box = std::min(to_box, segment_distance(s.a, box[k], box[(k + 1) % 4]));
              if (s.face != l->side.face || to_box >= 1e-6) return false;
              Vec2 end = s.b;
              for (std::size_t lines = 1; lines < layout.leaders.size(); ++lines) {
                const auto next = std::find_if(
                    layout.leaders.begin(), layout.leaders.end(), [&](const Segment& t) {
                      return &t != &s && t.face == s.face && norm(t.a - end) < 1e-9;
                    });
                if (next == layout.leaders.end()) break;
                end = next->b;
              }
              return segment_distance(end, a, b) < 1e-6;
            });
        if (led) {
          EXPECT_NEAR(l->size, kLegibleLabelMm, 1e-9) << name << " label " << l->text;
          ++far;
          continue;
        }
        if (inside_face(*l, tri)) continue;
        // Too small for its face: at least 1.5 mm on its side's glue tab, or beside its edge on
        // the face's side of it.
        EXPECT_GE(l->size, kLegibleLabelMm - 1e-9) << name << " label " << l->text;
        const Tab* tab = nullptr;
        for (const Tab& t : layout.tabs)
          if (t.edge == l->edge && t.side.face == l->side.face && t.side.k == l->side.k) tab = &t;
        bool on_tab = tab != nullptr;
        for (Vec2 p : box) on_tab = on_tab && point_in_quad(p, tab->corners);
        const bool face_side = cross(b - a, l->at - a) * cross(b - a, c - a) > 0;
        EXPECT_TRUE(on_tab || (face_side && std::abs(l->size - kLegibleLabelMm) < 1e-9))
            << name << " label " << l->text << " is neither in its face, on its tab, beside "
            << "its edge nor led to it";
        if (!on_tab) {
          // Beside its edge: its centre at most 2.7 of its height from the edge's line, and
          // along it at most one height past either end.
          const double len = norm(b - a);
          const Vec2 d = (1 / len) * (b - a);
          const double along = dot(l->at - a, d), off = std::abs(cross(d, l->at - a));
          EXPECT_LE(off, 2.7 * kLegibleLabelMm + 1e-6) << name << " label " << l->text;
          EXPECT_GE(along, -kLegibleLabelMm - 1e-6) << name << " label " << l->text;
          EXPECT_LE(along, len + kLegibleLabelMm + 1e-6) << name << " label " << l->text;
          // No cut line (nor tab hinge) between it and its edge: past one, it would be cut away
          // from the edge it names.
          const Vec2 e = a + std::clamp(along / len, 0.0, 1.0) * (b - a);
          const double reach = norm(l->at - e);
          if (reach > 0.05) {
            const Vec2 near = e + (0.05 / reach) * (l->at - e);
            std::size_t past = 0;
            for (const Segment& c : layout.cut) past += segments_cross(l->at, near, c.a, c.b);
            for (const Tab& t : layout.tabs)
              past += segments_cross(l->at, near, t.corners[0], t.corners[1]);
            EXPECT_EQ(past, 0u) << name << " label " << l->text << " lies past a cut line";
          }
        }
      }
    }
    for (const auto& [text, n] : texts) EXPECT_EQ(n, 1) << name << ": label " << text << " reused";
    // Each leader's first line starts at its label; the next, after a bend, where it ends.
    std::size_t firsts = 0;
    for (const Segment& s : layout.leaders)
      firsts += std::none_of(layout.leaders.begin(), layout.leaders.end(), [&](const Segment& t) {
        return t.face == s.face && norm(t.b - s.a) < 1e-9;
      });
    EXPECT_EQ(far, firsts) << name << ": leaders to no label";
    EXPECT_LE(layout.leaders.size(), 4 * firsts) << name << ": a leader of more than four lines";
    // No two labels meet, of one face or of two: a label moved beside its edge reaches over folds
    // into the faces around, and must not print over their labels (by the labels' boxes, pairs
    // taken in a sweep over x). Two labels inside their faces meet only where the faces do (the
    // BFS nets overlap), so of two faces, one must be moved.
    std::vector<std::pair<Box2, const Label*>> boxes;
    for (const Label& l : layout.labels) {
      if (l.text.empty()) continue;
      Box2 b = Box2::empty();
      for (Vec2 p : label_box(l)) b.add(p);
      boxes.emplace_back(b, &l);
    }
    std::sort(boxes.begin(), boxes.end(),
              [](const auto& a, const auto& b) { return a.first.lo.x < b.first.lo.x; });
    int meeting = 0;
    for (std::size_t i = 0; i < boxes.size(); ++i)
      for (std::size_t j = i + 1; j < boxes.size() && boxes[j].first.lo.x <= boxes[i].first.hi.x;
           ++j) {
        if (boxes[j].first.lo.y > boxes[i].first.hi.y || boxes[j].first.hi.y < boxes[i].first.lo.y)
          continue;
        const Label& la = *boxes[i].second;
        const Label& lb = *boxes[j].second;
        if (la.side.face != lb.side.face && inside_face(la, layout.faces[la.side.face]) &&
            inside_face(lb, layout.faces[lb.side.face]))
          continue;
        const auto a = label_box(la), b = label_box(lb);
        if (intersection_area({a.begin(), a.end()}, {b.begin(), b.end()}) > 1e-9 && ++meeting <= 3)
          ADD_FAILURE() << name << ": labels " << boxes[i].second->text << " (face "
                        << boxes[i].second->side.face << ") and " << boxes[j].second->text
                        << " (face " << boxes[j].second->side.face << ") meet";
      }
    EXPECT_EQ(meeting, 0) << name << ": pairs of labels that meet";
  }
}

// The cut edges are numbered 1 to N, the shortest (whose labels have the least room) with the
// narrowest numbers: along the edges from the shortest, a label's text never gets narrower.
TEST(Labels, TheShortestCutEdgesPrintTheNarrowestNumbers) {
  for (std::size_t n = 0; n < all_nets().size(); ++n) {
    const std::string& name = all_nets()[n].name;
    const PrintLayout& layout = all_layouts()[n];
    std::map<int, std::string> text;  // each number's labels' text
    for (const Label& l : layout.labels) text[layout.edges[l.edge].cut_index + 1] = l.text;
    std::vector<std::pair<double, int>> cut;  // printed length, number
    for (const NetEdge& e : layout.edges) {
      if (e.cut_index < 0) continue;
      const auto& tri = layout.faces[e.a.face];
      cut.emplace_back(norm(tri[(e.a.k + 1) % 3] - tri[e.a.k]), e.cut_index + 1);
    }
    ASSERT_FALSE(cut.empty()) << name;
    ASSERT_EQ(text.size(), cut.size()) << name;
    std::vector<int> numbers;
    for (const auto& c : cut) numbers.push_back(c.second);
    std::sort(numbers.begin(), numbers.end());
    for (std::size_t i = 0; i < numbers.size(); ++i) ASSERT_EQ(numbers[i], static_cast<int>(i) + 1);
    std::sort(cut.begin(), cut.end());
    // Lengths measured here and where the edges were numbered may differ in their last bits.
    const double tolerance = 1e-9 * cut.back().first;
    double widest = 0;  // the widest text of the edges shorter than edge i by the tolerance
    for (std::size_t i = 0, shorter = 0; i < cut.size(); ++i) {
      for (; cut[shorter].first < cut[i].first - tolerance; ++shorter)
        widest = std::max(widest, label_chars(text[cut[shorter].second]));
      EXPECT_GE(label_chars(text[cut[i].second]), widest)
          << name << ": edge " << cut[i].second << " (" << cut[i].first
          << " mm) prints a narrower number than a shorter edge";
    }
    const auto one =
        std::find_if(cut.begin(), cut.end(), [](const auto& c) { return c.second == 1; });
    EXPECT_LE(one->first, cut.front().first + tolerance) << name << ": 1 is not the shortest edge";
  }
}

// The labels of one face, as their face holds them, stand apart by 0.15 of the smaller one's
// height: touching at the face's corner, two labels read as one ("4→P260→P2": the Duck at the
// defaults had 32 such pairs). (A label moved to the legible size only keeps clear of the others'
// boxes, docs/print.md, "Labels".)
TEST(Labels, TheLabelsOfOneFaceStandApart) {
  for (std::size_t n = 0; n < all_nets().size(); ++n) {
    const std::string& name = all_nets()[n].name;
    const PrintLayout& layout = all_layouts()[n];
    std::map<int, std::vector<const Label*>> by_face;
    for (const Label& l : layout.labels)
      if (!l.text.empty() && l.size != kLegibleLabelMm && inside_face(l, layout.faces[l.side.face]))
        by_face[l.side.face].push_back(&l);
    int close = 0;
    for (const auto& [face, labels] : by_face)
      for (std::size_t i = 0; i < labels.size(); ++i)
        for (std::size_t j = i + 1; j < labels.size(); ++j) {
          const auto a = label_box(*labels[i]), b = label_box(*labels[j]);
          double apart = INFINITY;
          if (intersection_area({a.begin(), a.end()}, {b.begin(), b.end()}) > 0) apart = 0;
          for (int k = 0; k < 4; ++k)
            for (int q = 0; q < 4; ++q) {
              apart = std::min(apart, segment_distance(a[k], b[q], b[(q + 1) % 4]));
              apart = std::min(apart, segment_distance(b[k], a[q], a[(q + 1) % 4]));
            }
          const double least = 0.15 * std::min(labels[i]->size, labels[j]->size);
          if (apart < least - 1e-9 && ++close <= 3)
            ADD_FAILURE() << name << ": labels " << labels[i]->text << " and " << labels[j]->text
                          << " of face " << face << " are " << apart << " mm apart, under "
                          << least;
        }
    EXPECT_EQ(close, 0) << name;
  }
}

// A label its face holds only under 1.5 mm prints on its glue tab wherever the tab has room for
// it at 1.5 mm: low on a tall tab over a short edge, where the tab is widest, although its narrow
// top would not hold the text (the milk truck's wheel arches had 0.5 mm labels so). Room, from
// the tab's corners alone: a box of the text's width (0.6 of its height a character) and 0.6 of
// its height more at each end, and 0.1 of its height more above and below, inside the tab.
TEST(Labels, ASmallLabelMovesOntoItsTabWhereTheTabHoldsIt) {
  std::size_t on_tabs = 0, checked = 0;
  for (std::size_t n = 0; n < all_nets().size(); ++n) {
    const std::string& name = all_nets()[n].name;
    const PrintLayout& layout = all_layouts()[n];
    for (const Label& l : layout.labels) {
      const Tab* tab = nullptr;
      for (const Tab& t : layout.tabs)
        if (t.edge == l.edge && t.side.face == l.side.face && t.side.k == l.side.k) tab = &t;
      if (tab == nullptr || l.text.empty()) continue;
      const auto box = label_box(l);
      bool on_tab = true;
      for (Vec2 p : box) on_tab = on_tab && point_in_quad(p, tab->corners);
      on_tabs += on_tab;
      if (l.size >= kLegibleLabelMm) continue;
      ++checked;
      // Where the text would go, in the tab's frame: along its base, upwards.
      const auto& c = tab->corners;
      const double base = norm(c[1] - c[0]);
      const Vec2 d = (1 / base) * (c[1] - c[0]), up{-d.y, d.x};
      const double h = dot(c[3] - c[0], up), size = kLegibleLabelMm;
      const double half_w = 0.5 * (0.6 * size * label_chars(l.text)) + 0.6 * size;
      bool room = false;
      for (double y = 0; y + 1.2 * size <= h && !room; y += 0.05)
        for (double u = half_w; u + half_w <= base && !room; u += 0.05) {
          const Vec2 at = c[0] + u * d + (y + 0.6 * size) * up;
          room = true;
          for (const double sx : {-1.0, 1.0})
            for (const double sy : {-1.0, 1.0})
              room = room && point_in_quad(at + (sx * half_w) * d + (sy * 0.6 * size) * up, c);
        }
      EXPECT_FALSE(room) << name << ": label " << l.text << " prints at " << l.size
                         << " mm although its tab holds it at 1.5 mm";
    }
  }
  EXPECT_GT(checked, 100u) << "labels under 1.5 mm with a tab: the test checks too few";
  EXPECT_GT(on_tabs, 50u);
}

/// True when two point sequences (a face's corners, a tab's, a line's ends) are the same, to the
/// bit.
bool same_points(const auto& a, const auto& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].x != b[i].x || a[i].y != b[i].y) return false;
  return true;
}

// A layout with its labels unplaced (LabelPass::Unplaced, the fit search's tries where labels
// do not count) has every face, tab, glue strip and line of the layout with them, to the bit:
// the search weighs the sheets of the print it will make. Its labels are there, each with its
// text, edge and side, but unsized; it has no leaders and no piece numbers.
TEST(Labels, UnplacedLabelsLeaveTheLayoutAsWithThem) {
  std::size_t leaders = 0, strips = 0;
  for (std::size_t n = 0; n < all_nets().size(); ++n) {
    const std::string& name = all_nets()[n].name;
    const PrintLayout& placed = all_layouts()[n];
    const PrintLayout unplaced =
        layout_net(all_nets()[n].mesh, all_print_nets()[n].net, {}, {}, {}, LabelPass::Unplaced);
    leaders += placed.leaders.size();
    strips += placed.strips.size();
    ASSERT_EQ(unplaced.faces.size(), placed.faces.size()) << name;
    for (std::size_t f = 0; f < placed.faces.size(); ++f)
      ASSERT_TRUE(same_points(unplaced.faces[f], placed.faces[f])) << name << ": face " << f;
    ASSERT_EQ(unplaced.tabs.size(), placed.tabs.size()) << name;
    for (std::size_t t = 0; t < placed.tabs.size(); ++t) {
      EXPECT_EQ(unplaced.tabs[t].edge, placed.tabs[t].edge) << name;
      EXPECT_TRUE(same_points(unplaced.tabs[t].corners, placed.tabs[t].corners)) << name;
    }
    ASSERT_EQ(unplaced.strips.size(), placed.strips.size()) << name;
    for (std::size_t t = 0; t < placed.strips.size(); ++t) {
      EXPECT_EQ(unplaced.strips[t].edge, placed.strips[t].edge) << name;
      EXPECT_EQ(unplaced.strips[t].text, placed.strips[t].text) << name;
      EXPECT_TRUE(same_points(unplaced.strips[t].corners, placed.strips[t].corners)) << name;
    }
    for (const auto lines : {&PrintLayout::cut, &PrintLayout::mountain, &PrintLayout::valley}) {
      const std::vector<Segment>& a = placed.*lines;
      const std::vector<Segment>& b = unplaced.*lines;
      ASSERT_EQ(a.size(), b.size()) << name;
      for (std::size_t i = 0; i < a.size(); ++i)
        EXPECT_TRUE(same_points(std::array{a[i].a, a[i].b}, std::array{b[i].a, b[i].b})) << name;
    }
    EXPECT_EQ(unplaced.size.x, placed.size.x) << name;
    EXPECT_EQ(unplaced.size.y, placed.size.y) << name;
    ASSERT_EQ(unplaced.labels.size(), placed.labels.size()) << name;
    for (std::size_t i = 0; i < placed.labels.size(); ++i) {
      EXPECT_EQ(unplaced.labels[i].edge, placed.labels[i].edge) << name;
      EXPECT_EQ(unplaced.labels[i].side.face, placed.labels[i].side.face) << name;
      EXPECT_EQ(unplaced.labels[i].size, 0) << name;
    }
    EXPECT_TRUE(unplaced.leaders.empty()) << name;
    EXPECT_TRUE(unplaced.piece_labels.empty()) << name;
  }
  // Nets whose layout places labels away from their edges and prints glue strips: what the
  // unplaced layout leaves out, and what it must keep.
  EXPECT_GT(leaders, 0u);
  EXPECT_GT(strips, 0u);
}

// Out of time for its labels (PrintOptions::label_seconds, which the fit search sets for the
// chosen print's labels from the time it has left), a layout moves none of them: each stays in
// its face at the size that fits it, with no leader, where the layout with time moves many
// (beside their edges, onto tabs, away with leaders). Its faces, tabs and glue strips are those of
// the layout with time.
TEST(Labels, OutOfTimeEachLabelStaysInItsFace) {
  PrintOptions hurried;
  hurried.label_seconds = 1e-9;
  std::size_t moved = 0, small = 0;
  for (std::size_t n = 0; n < all_nets().size(); ++n) {
    const std::string& name = all_nets()[n].name;
    const PrintLayout& timely = all_layouts()[n];
    const PrintLayout late = layout_net(all_nets()[n].mesh, all_print_nets()[n].net, hurried);
    ASSERT_EQ(late.faces.size(), timely.faces.size()) << name;
    for (std::size_t f = 0; f < late.faces.size(); ++f)
      ASSERT_TRUE(same_points(late.faces[f], timely.faces[f])) << name << ": face " << f;
    EXPECT_EQ(late.tabs.size(), timely.tabs.size()) << name;
    EXPECT_EQ(late.strips.size(), timely.strips.size()) << name;
    EXPECT_TRUE(late.leaders.empty()) << name;
    ASSERT_EQ(late.labels.size(), timely.labels.size()) << name;
    for (std::size_t i = 0; i < late.labels.size(); ++i) {
      const Label& l = late.labels[i];
      EXPECT_GT(l.size, 0) << name << " label " << l.text;
      EXPECT_TRUE(inside_face(l, late.faces[l.side.face])) << name << " label " << l.text;
      small += l.size < kLegibleLabelMm;
      const Label& t = timely.labels[i];
      moved += !inside_face(t, timely.faces[t.side.face]);
    }
  }
  // Labels the layout with time moved, and labels the late one leaves small: the test can tell.
  EXPECT_GT(moved, 100u);
  EXPECT_GE(small, moved);
}

TEST(Layout, ScaleMakesTheLongestModelSideTheTargetSize) {
  Mesh m = test::cube();
  for (Vec3& v : m.vertices) v = Vec3{3 * v.x, v.y, 0.5 * v.z};  // 3 x 1 x 0.5 box
  PrintOptions options;
  options.size_mm = 150;
  const PrintLayout layout = layout_net(m, test::bfs_net(m), options);
  EXPECT_DOUBLE_EQ(layout.scale, 50);
  // The longest face edge of the layout is the 3-unit side: 150 mm.
  double longest = 0;
  for (const auto& t : layout.faces)
    for (int k = 0; k < 3; ++k) longest = std::max(longest, norm(t[(k + 1) % 3] - t[k]));
  EXPECT_NEAR(longest, std::hypot(150.0, 50.0), 1e-9);  // the quad diagonals
  options.scale = 2;
  EXPECT_DOUBLE_EQ(layout_net(m, test::bfs_net(m), options).scale, 2);
  Net broken = test::bfs_net(m);
  broken.points[3][1].y = std::nan("");
  EXPECT_THROW(layout_net(m, broken, options), std::invalid_argument);
  broken.points.pop_back();
  EXPECT_THROW(layout_net(m, broken, options), std::invalid_argument);
  EXPECT_THROW(layout_net(Mesh{}, Net{}, options), std::invalid_argument);
  options.tab_angle_deg = 0;
  EXPECT_THROW(layout_net(m, test::bfs_net(m), options), std::invalid_argument);
}

/// Runs a shell command; returns its exit status, or -1 when `tool` is not installed.
int run_tool(const std::string& tool, const std::string& args) {
  if (std::system(("command -v " + tool + " >/dev/null 2>&1").c_str()) != 0) return -1;
  return std::system((tool + " " + args).c_str());
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("papernet_svg_test_" + name)).string();
}

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

int count(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  return static_cast<int>(
      std::distance(std::sregex_iterator(text.begin(), text.end(), re), std::sregex_iterator()));
}

/// The text between <g id="name" ...> and its </g> (groups are not nested).
std::string group(const std::string& svg, const std::string& id) {
  const auto start = svg.find("<g id=\"" + id + "\"");
  if (start == std::string::npos) return {};
  return svg.substr(start, svg.find("</g>", start) - start);
}

TEST(Svg, HasLayersTabsAndLabelsAndParsesAndRenders) {
  const auto meshes = test::test_data_meshes();
  ASSERT_FALSE(meshes.empty());
  const Mesh& mesh = meshes.front().second;
  const PrintLayout layout = layout_net(mesh, test::bfs_net(mesh), {});
  const std::string svg = write_net_svg(layout, 5);
  EXPECT_NE(svg.find("viewBox=\"0 0 "), std::string::npos);
  EXPECT_NE(svg.find("mm\" height=\""), std::string::npos);
  for (const char* id : {"faces", "tabs", "strips", "cut", "mountain", "valley", "labels"})
    EXPECT_NE(svg.find(std::string("<g id=\"") + id + "\""), std::string::npos) << id;
  EXPECT_EQ(count(group(svg, "tabs"), "<polygon "), static_cast<int>(layout.tabs.size()));
  EXPECT_EQ(count(group(svg, "labels"), "<text "), 2 * layout.cut_edges);
  EXPECT_EQ(count(group(svg, "faces"), "<polygon "), static_cast<int>(mesh.faces.size()));
  EXPECT_NE(group(svg, "mountain").find("stroke-dasharray=\"2 1\""), std::string::npos);
  EXPECT_NE(group(svg, "valley").find("stroke-dasharray=\"2 0.7 0.4 0.7\""), std::string::npos);
  EXPECT_EQ(group(svg, "cut").find("dasharray"), std::string::npos);
  EXPECT_NE(svg.find("data-tabs-omitted=\"" + std::to_string(layout.omitted_tabs.size())),
            std::string::npos);
  // With strips only: one outline, a seam and the edge's label twice per strip.
  PrintOptions strip_options;
  strip_options.tabs = TabMode::Strips;
  const PrintLayout stripped = layout_net(mesh, test::bfs_net(mesh), strip_options);
  ASSERT_GT(stripped.strips.size(), 0u);
  const std::string strip_svg = write_net_svg(stripped, 5);
  const std::string strips = group(strip_svg, "strips");
  EXPECT_EQ(count(strips, "<polygon "), static_cast<int>(stripped.strips.size()));
  EXPECT_EQ(count(strips, "<text "), 2 * static_cast<int>(stripped.strips.size()));
  EXPECT_EQ(count(group(strip_svg, "tabs"), "<polygon "), 0);
  EXPECT_NE(strip_svg.find("data-strips=\"" + std::to_string(stripped.strips.size())),
            std::string::npos);
  for (const GlueStrip& st : stripped.strips)
    EXPECT_NE(strips.find(">" + st.text + "</text>"), std::string::npos) << st.text;

  const std::string path = temp_path("net.svg"), png = temp_path("net.png");
  write(path, svg);
  const int xml = run_tool("xmllint", "--noout " + path);
  if (xml == -1) GTEST_SKIP() << "xmllint missing: install libxml2-utils (scripts/install-deps.sh)";
  EXPECT_EQ(xml, 0) << "xmllint rejects " << path;
  const int rsvg = run_tool("rsvg-convert", "-o " + png + " " + path);
  if (rsvg == -1) GTEST_SKIP() << "rsvg-convert missing: install librsvg2-bin";
  EXPECT_EQ(rsvg, 0) << "rsvg-convert cannot render " << path;
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
  std::filesystem::remove(path);
  std::filesystem::remove(png);
}

}  // namespace
}  // namespace papernet
