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
#include "tests/net_fixtures.h"

namespace papernet {
namespace {

double signed_area(const std::vector<Vec2>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * a;
}

/// Area of the intersection of two convex polygons (Sutherland-Hodgman clipping): an
/// independent check of the separating-axis test the tab placer uses.
double intersection_area(std::vector<Vec2> subject, std::vector<Vec2> clip) {
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
  return subject.size() < 3 ? 0 : std::abs(signed_area(subject));
}

bool point_in_triangle(Vec2 p, const std::array<Vec2, 3>& t, double tol) {
  for (int k = 0; k < 3; ++k) {
    const Vec2 a = t[k], b = t[(k + 1) % 3];
    if (cross(b - a, p - a) / norm(b - a) < -tol) return false;
  }
  return true;
}

/// Nets to check: the cube, octahedron and tetrahedron, and every mesh of tests/data.
std::vector<std::pair<std::string, Mesh>> all_meshes() {
  auto meshes = testing::test_data_meshes();
  meshes.emplace_back("cube", testing::cube());
  meshes.emplace_back("octahedron", testing::octahedron());
  meshes.emplace_back("tetrahedron", testing::tetrahedron());
  return meshes;
}

TEST(Tabs, ConvexOverlapIgnoresTouchingAndSeesCrossing) {
  const std::vector<Vec2> a = {{0, 0}, {1, 0}, {0, 1}}, b = {{1, 0}, {0, 1}, {1, 1}};
  EXPECT_FALSE(convex_overlap(a, b, 1e-9));  // share an edge
  const std::vector<Vec2> c = {{0.4, 0.4}, {2, 0.4}, {2, 2}};
  EXPECT_TRUE(convex_overlap(a, c, 1e-9));
  const std::vector<Vec2> d = {{1, 1}, {2, 1}, {2, 2}};
  EXPECT_FALSE(convex_overlap(a, d, 1e-9));  // disjoint
}

TEST(Tabs, NeverOverlapFacesOrTabsAndEveryCutEdgeHasOneTabOrIsCounted) {
  for (const auto& [name, mesh] : all_meshes()) {
    const Net net = testing::bfs_net(mesh);
    PrintOptions options;
    options.size_mm = 200;
    const PrintLayout layout = layout_net(mesh, net, options);
    // Tolerance: 1e-6 of a square millimetre of shared area.
    const double tol = 1e-6;
    for (std::size_t t = 0; t < layout.tabs.size(); ++t) {
      const Tab& tab = layout.tabs[t];
      const std::vector<Vec2> tp(tab.corners.begin(), tab.corners.end());
      EXPECT_GT(signed_area(tp), 0) << name << " tab " << t;
      for (std::size_t f = 0; f < layout.faces.size(); ++f) {
        const auto& tri = layout.faces[f];
        ASSERT_LE(intersection_area(tp, {tri.begin(), tri.end()}), tol)
            << name << ": tab " << t << " overlaps face " << f;
      }
      for (std::size_t u = t + 1; u < layout.tabs.size(); ++u) {
        const auto& o = layout.tabs[u].corners;
        ASSERT_LE(intersection_area(tp, {o.begin(), o.end()}), tol)
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
      // The tab's base is exactly the side it hangs from.
      const auto& tri = layout.faces[tab.side.face];
      EXPECT_NEAR(norm(tab.corners[1] - tri[tab.side.k]), 0, 1e-9);
      EXPECT_NEAR(norm(tab.corners[0] - tri[(tab.side.k + 1) % 3]), 0, 1e-9);
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
  for (const auto& [name, mesh] : all_meshes()) {
    const PrintLayout layout = layout_net(mesh, testing::bfs_net(mesh), {});
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
