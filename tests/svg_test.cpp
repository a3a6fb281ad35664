#include "api/svg.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>

#include "api/print_layout.h"
#include "api/tabs.h"
#include "core/unfolding.h"
#include "tests/net_fixtures.h"

namespace papernet {
namespace {

double signed_area(const std::vector<Vec2>& p) {
  double a = 0;  // relative to p[0]: absolute coordinates would drown tiny areas in rounding
  for (std::size_t i = 1; i + 1 < p.size(); ++i) a += cross(p[i] - p[0], p[i + 1] - p[0]);
  return 0.5 * a;
}

/// Intersection of two convex polygons (Sutherland-Hodgman clipping): an independent check of
/// the separating-axis test the tab placer uses.
std::vector<Vec2> intersection(std::vector<Vec2> subject, std::vector<Vec2> clip) {
  if (signed_area(clip) < 0) std::reverse(clip.begin(), clip.end());
  for (std::size_t i = 0; i < clip.size() && !subject.empty(); ++i) {
    const Vec2 a = clip[i], b = clip[(i + 1) % clip.size()];
    auto inside = [&](Vec2 p) { return cross(b - a, p - a) >= 0; };
    std::vector<Vec2> out;
    for (std::size_t j = 0; j < subject.size(); ++j) {
      const Vec2 p = subject[j], q = subject[(j + 1) % subject.size()];
      const bool ip = inside(p), iq = inside(q);
      if (ip) out.push_back(p);
      if (ip != iq) {
        const double t = cross(b - a, p - a) / (cross(b - a, p - a) - cross(b - a, q - a));
        out.push_back(p + t * (q - p));
      }
    }
    subject = std::move(out);
  }
  return subject;
}

double intersection_area(std::vector<Vec2> a, std::vector<Vec2> b) {
  const auto p = intersection(std::move(a), std::move(b));
  return p.size() < 3 ? 0 : std::abs(signed_area(p));
}

/// Mean thickness of the intersection (area / longest extent), in mm: how deep two shapes
/// really overlap. Shapes that only touch give 0 up to rounding.
double overlap_thickness(std::vector<Vec2> a, std::vector<Vec2> b) {
  const auto p = intersection(std::move(a), std::move(b));
  if (p.size() < 3) return 0;
  double extent = 0;
  for (Vec2 u : p)
    for (Vec2 v : p) extent = std::max(extent, norm(u - v));
  return extent > 0 ? std::abs(signed_area(p)) / extent : 0;
}

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

/// Nets to check: breadth-first nets (overlapping, crowded) of the cube, octahedron,
/// tetrahedron and every mesh of tests/data, and the Tabu Unfolder's overlap-free nets of the
/// tests/data meshes. Built once.
const std::vector<NamedNet>& all_nets() {
  static const std::vector<NamedNet> nets = [] {
    std::vector<NamedNet> out;
    auto meshes = testing::test_data_meshes();
    for (const auto& [name, mesh] : meshes) {
      Progress quiet;
      TabuOptions options;
      options.time_limit_seconds = 30;
      out.push_back({name + " (TU)", mesh, unfold_tabu(mesh, options, quiet).net});
    }
    meshes.emplace_back("cube", testing::cube());
    meshes.emplace_back("octahedron", testing::octahedron());
    meshes.emplace_back("tetrahedron", testing::tetrahedron());
    for (auto& [name, mesh] : meshes)
      out.push_back({name + " (BFS)", mesh, testing::bfs_net(mesh)});
    return out;
  }();
  return nets;
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

TEST(Tabs, NeverOverlapFacesOrTabsOneTabPerCutEdgeOrCountedOutlineClosed) {
  ASSERT_GE(all_nets().size(), 19u);
  for (const auto& [name, mesh, net] : all_nets()) {
    PrintOptions options;
    options.size_mm = 200;
    const PrintLayout layout = layout_net(mesh, net, options);
    expect_cut_sides_covered(layout, name);
    // Overlaps thinner than 10 nm are touching (the placer's tolerance is a 1 nm depth).
    const double tol = 1e-5;
    for (std::size_t t = 0; t < layout.tabs.size(); ++t) {
      const Tab& tab = layout.tabs[t];
      const std::vector<Vec2> tp(tab.corners.begin(), tab.corners.end());
      EXPECT_GT(signed_area(tp), 0) << name << " tab " << t;
      for (std::size_t f = 0; f < layout.faces.size(); ++f) {
        const auto& tri = layout.faces[f];
        ASSERT_LE(overlap_thickness(tp, {tri.begin(), tri.end()}), tol)
            << name << ": tab " << t << " overlaps face " << f;
      }
      for (std::size_t u = t + 1; u < layout.tabs.size(); ++u) {
        const auto& o = layout.tabs[u].corners;
        ASSERT_LE(overlap_thickness(tp, {o.begin(), o.end()}), tol)
            << name << ": tabs " << t << " and " << u << " overlap";
      }
    }
    std::map<int, int> tabs_per_edge;
    for (const Tab& tab : layout.tabs) {
      ++tabs_per_edge[tab.edge];
      const NetEdge& e = layout.edges[tab.edge];
      ASSERT_GE(e.cut_index, 0) << name;
      const bool on_a = tab.side.face == e.a.face && tab.side.k == e.a.k;
      const bool on_b = tab.side.face == e.b.face && tab.side.k == e.b.k;
      EXPECT_TRUE(on_a || on_b) << name;
      // The tab's base lies on the side it hangs from, and covers at least a third of it.
      const auto& tri = layout.faces[tab.side.face];
      const Vec2 e0 = tri[tab.side.k], e1 = tri[(tab.side.k + 1) % 3];
      const double len = norm(e1 - e0);
      for (Vec2 c : {tab.corners[0], tab.corners[1]}) {
        EXPECT_NEAR(cross(e1 - e0, c - e0) / len, 0, 1e-9) << name;
        EXPECT_GE(dot(c - e0, e1 - e0) / len, -1e-9) << name;
        EXPECT_LE(dot(c - e0, e1 - e0) / len, len + 1e-9) << name;
      }
      EXPECT_GE(norm(tab.corners[0] - tab.corners[1]), len / 3) << name;
    }
    for (int e : layout.omitted_tabs) ++tabs_per_edge[e];
    int cut_edges = 0;
    for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
      if (layout.edges[e].cut_index < 0) continue;
      ++cut_edges;
      EXPECT_EQ(tabs_per_edge[e], 1) << name << " edge " << e;
    }
    EXPECT_EQ(cut_edges, layout.cut_edges);
    EXPECT_EQ(layout.tabs.size() + layout.omitted_tabs.size(), std::size_t(cut_edges)) << name;
    // Faces: F - 1 tree edges, so E - F + 1 cut edges (closed meshes: all interior).
    EXPECT_GT(cut_edges, 0) << name;
    std::printf("%s: %zu faces, %d cut edges, %zu tabs, %zu omitted\n", name.c_str(),
                layout.faces.size(), cut_edges, layout.tabs.size(), layout.omitted_tabs.size());
  }
}

TEST(Labels, TwoMatchingLabelsPerCutEdgeInsideTheirFaces) {
  for (const auto& [name, mesh, net] : all_nets()) {
    const PrintLayout layout = layout_net(mesh, net, {});
    std::map<int, std::vector<const Label*>> by_edge;
    for (const Label& l : layout.labels) by_edge[l.edge].push_back(&l);
    EXPECT_EQ(static_cast<int>(by_edge.size()), layout.cut_edges) << name;
    std::map<std::string, int> texts;
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
        for (Vec2 p : label_box(*l))
          EXPECT_TRUE(point_in_triangle(p, tri, 1e-9)) << name << " label " << l->text;
      }
    }
    for (const auto& [text, n] : texts) EXPECT_EQ(n, 1) << name << ": label " << text << " reused";
    // Labels sharing a face (a face with two or three cut edges) stay apart.
    std::map<int, std::vector<const Label*>> by_face;
    for (const Label& l : layout.labels) by_face[l.side.face].push_back(&l);
    for (const auto& [f, labels] : by_face)
      for (std::size_t i = 0; i < labels.size(); ++i)
        for (std::size_t j = i + 1; j < labels.size(); ++j) {
          const auto a = label_box(*labels[i]), b = label_box(*labels[j]);
          EXPECT_LE(intersection_area({a.begin(), a.end()}, {b.begin(), b.end()}), 1e-9)
              << name << ": labels " << labels[i]->text << " and " << labels[j]->text
              << " collide in face " << f;
        }
  }
}

TEST(Layout, ScaleMakesTheLongestModelSideTheTargetSize) {
  Mesh m = testing::cube();
  for (Vec3& v : m.vertices) v = Vec3{3 * v.x, v.y, 0.5 * v.z};  // 3 x 1 x 0.5 box
  PrintOptions options;
  options.size_mm = 150;
  const PrintLayout layout = layout_net(m, testing::bfs_net(m), options);
  EXPECT_DOUBLE_EQ(layout.scale, 50);
  // The longest face edge of the layout is the 3-unit side: 150 mm.
  double longest = 0;
  for (const auto& t : layout.faces)
    for (int k = 0; k < 3; ++k) longest = std::max(longest, norm(t[(k + 1) % 3] - t[k]));
  EXPECT_NEAR(longest, std::hypot(150.0, 50.0), 1e-9);  // the quad diagonals
  options.scale = 2;
  EXPECT_DOUBLE_EQ(layout_net(m, testing::bfs_net(m), options).scale, 2);
  Net broken = testing::bfs_net(m);
  broken.points[3][1].y = std::nan("");
  EXPECT_THROW(layout_net(m, broken, options), std::invalid_argument);
  broken.points.pop_back();
  EXPECT_THROW(layout_net(m, broken, options), std::invalid_argument);
  EXPECT_THROW(layout_net(Mesh{}, Net{}, options), std::invalid_argument);
  options.tab_angle_deg = 0;
  EXPECT_THROW(layout_net(m, testing::bfs_net(m), options), std::invalid_argument);
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
  const auto meshes = testing::test_data_meshes();
  ASSERT_FALSE(meshes.empty());
  const Mesh& mesh = meshes.front().second;
  const PrintLayout layout = layout_net(mesh, testing::bfs_net(mesh), {});
  const std::string svg = write_net_svg(layout, 5);
  EXPECT_NE(svg.find("viewBox=\"0 0 "), std::string::npos);
  EXPECT_NE(svg.find("mm\" height=\""), std::string::npos);
  for (const char* id : {"faces", "tabs", "cut", "mountain", "valley", "labels"})
    EXPECT_NE(svg.find(std::string("<g id=\"") + id + "\""), std::string::npos) << id;
  EXPECT_EQ(count(group(svg, "tabs"), "<polygon "), static_cast<int>(layout.tabs.size()));
  EXPECT_EQ(count(group(svg, "labels"), "<text "), 2 * layout.cut_edges);
  EXPECT_EQ(count(group(svg, "faces"), "<polygon "), static_cast<int>(mesh.faces.size()));
  EXPECT_NE(group(svg, "mountain").find("stroke-dasharray=\"2 1\""), std::string::npos);
  EXPECT_NE(group(svg, "valley").find("stroke-dasharray=\"2 0.7 0.4 0.7\""), std::string::npos);
  EXPECT_EQ(group(svg, "cut").find("dasharray"), std::string::npos);
  EXPECT_NE(svg.find("data-tabs-omitted=\"" + std::to_string(layout.omitted_tabs.size())),
            std::string::npos);

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
