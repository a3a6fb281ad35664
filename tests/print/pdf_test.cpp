#include "print/pdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>

#include "core/errors.h"
#include "core/io/load.h"
#include "print/pages.h"
#include "print/svg.h"
#include "tests/support/meshes.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

/// Output of a shell command, or nullopt-like "" with ok=false when the tool is missing.
struct ToolRun {
  bool present = false;
  int status = 0;
  std::string out;
};
ToolRun run(const std::string& tool, const std::string& args) {
  ToolRun r;
  if (std::system(("command -v " + tool + " >/dev/null 2>&1").c_str()) != 0) return r;
  r.present = true;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((tool + " " + args).c_str(), "r"), pclose);
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, pipe.get())) r.out.append(buf, n);
  r.status = pclose(pipe.release());
  return r;
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("papernet_pdf_test_" + name)).string();
}

/// Occurrences of `what` in `text`.
int count_of(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// Pages needed for `content` on printable `room` with `overlap`, computed independently of
/// paginate: the smallest n with n * room - (n - 1) * overlap >= content.
int tiles(double content, double room, double overlap) {
  int n = 1;
  while (n * room - (n - 1) * overlap < content) ++n;
  return n;
}

TEST(Pages, ParsePaperAndLengths) {
  EXPECT_DOUBLE_EQ(parse_paper("a4").height, 297);
  EXPECT_DOUBLE_EQ(parse_paper("Letter").width, 215.9);
  const Paper p = parse_paper("300x200mm");
  EXPECT_DOUBLE_EQ(p.width, 200);
  EXPECT_DOUBLE_EQ(p.height, 300);
  EXPECT_DOUBLE_EQ(parse_paper("A5").width, 148);
  EXPECT_DOUBLE_EQ(parse_paper("a5").height, 210);
  EXPECT_DOUBLE_EQ(parse_paper("LEGAL").height, 355.6);
  EXPECT_DOUBLE_EQ(parse_paper("Tabloid").width, 279.4);
  EXPECT_DOUBLE_EQ(parse_paper("tabloid").height, 431.8);
  EXPECT_THROW(parse_paper("B5"), std::invalid_argument);
  try {
    parse_paper("A6");
    ADD_FAILURE() << "A6 taken";
  } catch (const InvalidOptionException& e) {  // the refusal lists what is taken
    EXPECT_NE(std::string(e.what()).find("A4, A3, A5, Letter, Legal, Tabloid, WxHmm"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(parse_paper("0x10mm"), std::invalid_argument);
  EXPECT_DOUBLE_EQ(parse_length_mm("200mm"), 200);
  EXPECT_DOUBLE_EQ(parse_length_mm("2cm"), 20);
  EXPECT_DOUBLE_EQ(parse_length_mm("1in"), 25.4);
  EXPECT_DOUBLE_EQ(parse_length_mm("15"), 15);
  EXPECT_THROW(parse_length_mm("-3mm"), std::invalid_argument);
  EXPECT_THROW(parse_length_mm("12 parsecs"), std::invalid_argument);
  PageOptions o;
  o.margin_mm = 120;
  try {
    o.validate();
    ADD_FAILURE() << "margins wider than the page passed";
  } catch (const InvalidOptionException& e) {
    EXPECT_EQ(e.option(), "margin_mm");
  }
  EXPECT_EQ(parse_paper("300x200").name, "300x200mm");
  // Paper too small for the tiles' overlap: the message gives the figures to change.
  PageOptions small;
  small.paper = parse_paper("30x30mm");
  try {
    small.validate();
    ADD_FAILURE() << "an overlap of half the printable side passed";
  } catch (const InvalidOptionException& e) {
    EXPECT_EQ(e.option(), "overlap_mm");
    EXPECT_NE(std::string(e.what()).find("(10 mm)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("30x30mm paper within margins of 10 mm prints 10 mm"),
              std::string::npos)
        << e.what();
  }
}

TEST(Pages, TilesCoverTheNetWithOverlapAndUseTheCheaperOrientation) {
  const Mesh mesh = test::octahedron();
  for (double size : {50.0, 200.0, 600.0}) {
    PrintOptions print;
    print.size_mm = size;
    PrintLayout layout = layout_net(mesh, test::bfs_net(mesh), print);
    const Vec2 before = layout.size;
    const auto labels_before = layout.labels;
    PageOptions o;  // A4, 10 mm margins, 10 mm overlap
    const PageLayout pages = paginate(layout, o);
    const int grid = std::min(tiles(before.x, 190, 10) * tiles(before.y, 277, 10),
                              tiles(before.y, 190, 10) * tiles(before.x, 277, 10));
    // Never more pages than the cheaper grid; fewer when tiles of it would be empty.
    EXPECT_LE(static_cast<int>(pages.pages.size()), grid) << size;
    EXPECT_GE(pages.rows * pages.cols, static_cast<int>(pages.pages.size()));
    // Every face corner is on some page's window; neighbouring windows share the overlap.
    for (const auto& tri : layout.faces)
      for (Vec2 p : tri) {
        bool seen = false;
        for (const Page& pg : pages.pages)
          seen |= p.x >= pg.lo.x - 1e-9 && p.x <= pg.hi.x + 1e-9 && p.y >= pg.lo.y - 1e-9 &&
                  p.y <= pg.hi.y + 1e-9;
        EXPECT_TRUE(seen);
      }
    // Labels still read upright (or vertically) and still fit their faces after any turn.
    ASSERT_EQ(layout.labels.size(), labels_before.size());
    for (const Label& l : layout.labels) {
      EXPECT_GE(std::cos(l.angle), -1e-9) << size;
      const auto& tri = layout.faces[l.side.face];
      for (Vec2 p : label_box(l))
        for (int k = 0; k < 3; ++k) EXPECT_GE(cross(tri[(k + 1) % 3] - tri[k], p - tri[k]), -1e-9);
    }
    for (const Page& a : pages.pages)
      for (const Page& b : pages.pages) {
        if (a.row == b.row && b.col == a.col + 1) {
          EXPECT_NEAR(a.hi.x - b.lo.x, 10, 1e-9);
        }
        if (a.col == b.col && b.row == a.row + 1) {
          EXPECT_NEAR(b.hi.y - a.lo.y, 10, 1e-9);
        }
      }
  }
}

TEST(Pages, EmptyTilesAreNotPrinted) {
  // Two small triangles in opposite corners of a 370 x 540 mm area: a 2 x 2 grid of A4 tiles
  // (portrait, 190 x 277 printable, 10 mm overlap) of which only the two corner tiles show
  // anything.
  PrintLayout layout;
  layout.faces = {{Vec2{0, 0}, Vec2{20, 0}, Vec2{0, 20}},
                  {Vec2{370, 540}, Vec2{350, 540}, Vec2{370, 520}}};
  layout.size = {370, 540};
  const PageLayout pages = paginate(layout, {});
  EXPECT_EQ(pages.rows * pages.cols, 4);
  ASSERT_EQ(pages.pages.size(), 2u);
  EXPECT_NE(pages.pages[0].row, pages.pages[1].row);
  EXPECT_NE(pages.pages[0].col, pages.pages[1].col);
}

TEST(Pages, AWideNetThatFitsEitherWayRunsAlongThePortraitPage) {
  PrintLayout layout;
  layout.faces = {{Vec2{0, 0}, Vec2{150, 0}, Vec2{0, 50}}};
  layout.size = {150, 50};
  const PageLayout pages = paginate(layout, {});
  ASSERT_EQ(pages.pages.size(), 1u);
  EXPECT_LT(pages.width, pages.height);  // portrait
  EXPECT_TRUE(pages.quarter_turn);
  EXPECT_DOUBLE_EQ(layout.size.x, 50);
  EXPECT_DOUBLE_EQ(layout.size.y, 150);
}

TEST(Pages, GlueStripsLandOnPagesAndTurnWithTheNet) {
  // A strip far from the net, which would need a page of its own, moves onto the net's page;
  // on real nets every strip prints whole on one page, whichever way the net is turned.
  PrintLayout layout;
  layout.faces = {{Vec2{0, 0}, Vec2{20, 0}, Vec2{0, 20}}};
  layout.strips = {{-1, {Vec2{350, 520}, Vec2{370, 520}, Vec2{370, 532}, Vec2{350, 532}}, "7", 3}};
  layout.size = {370, 540};
  const PageLayout lone = paginate(layout, {});
  ASSERT_EQ(lone.pages.size(), 1u);
  for (Vec2 p : layout.strips[0].corners) {
    EXPECT_TRUE(p.x >= lone.pages[0].lo.x && p.x <= lone.pages[0].hi.x) << p.x;
    EXPECT_TRUE(p.y >= lone.pages[0].lo.y && p.y <= lone.pages[0].hi.y) << p.y;
    EXPECT_FALSE(convex_overlap(layout.strips[0].corners, layout.faces[0], 0));
  }
  EXPECT_EQ(layout.strips[0].text, "7");
  Mesh mesh;
  for (auto& [name, m] : test::test_data_meshes())
    if (name == "sample.obj") mesh = std::move(m);
  ASSERT_FALSE(mesh.faces.empty());
  for (double size : {100.0, 400.0}) {
    PrintOptions print;
    print.size_mm = size;
    print.tabs = TabMode::Strips;
    PrintLayout net = layout_net(mesh, test::bfs_net(mesh), print);
    ASSERT_EQ(net.strips.size(), static_cast<std::size_t>(net.cut_edges));
    const PageLayout pages = paginate(net, {});
    int drawn = 0;
    for (int i = 0; i < static_cast<int>(pages.pages.size()); ++i)
      for (const Shape& s : draw_page(net, pages, i).shapes)
        drawn += s.layer == Layer::Strips && s.closed;
    EXPECT_GE(drawn, static_cast<int>(net.strips.size())) << size;
    // Every strip prints whole on one page (strips are moved onto the net's pages for that).
    for (const GlueStrip& strip : net.strips) {
      bool whole = false;
      for (const Page& page : pages.pages) {
        bool inside = true;
        for (Vec2 p : strip.corners)
          inside = inside && p.x >= page.lo.x - 1e-9 && p.x <= page.hi.x + 1e-9 &&
                   p.y >= page.lo.y - 1e-9 && p.y <= page.hi.y + 1e-9;
        whole = whole || inside;
      }
      EXPECT_TRUE(whole) << size << ": strip " << strip.text << " is on no page whole";
    }
    if (size == 400) {
      EXPECT_GT(pages.pages.size(), 1u);
    }
  }
}

TEST(Pdf, HasTheExpectedPageCountAndRenders) {
  const Mesh mesh = test::octahedron(-0.4);
  for (double size : {60.0, 400.0}) {
    PrintOptions print;
    print.size_mm = size;
    PrintLayout layout = layout_net(mesh, test::bfs_net(mesh), print);
    const PageLayout pages = paginate(layout, {});
    const std::string pdf = write_pdf(layout, pages);
    ASSERT_EQ(pdf.rfind("%PDF-", 0), 0u);
    const std::string path = temp_path(std::to_string(int(size)) + ".pdf");
    std::ofstream(path, std::ios::binary) << pdf;
    const ToolRun info = run("pdfinfo", path);
    if (!info.present) GTEST_SKIP() << "pdfinfo missing: install poppler-utils";
    ASSERT_EQ(info.status, 0) << info.out;
    const auto at = info.out.find("Pages:");
    ASSERT_NE(at, std::string::npos);
    EXPECT_EQ(std::stoi(info.out.substr(at + 6)), static_cast<int>(pages.pages.size()));
    EXPECT_NE(info.out.find(std::to_string(layout.strips.size()) + " glue strips, " +
                            std::to_string(layout.omitted_tabs.size()) + " tabs omitted"),
              std::string::npos)
        << info.out;
    if (size == 60) {
      EXPECT_EQ(pages.pages.size(), 1u);
    }
    if (size == 400) {
      EXPECT_GT(pages.pages.size(), 1u);
    }
    const ToolRun png = run("pdftoppm", "-r 30 -png -f 1 -l 1 " + path + " " + path);
    if (png.present) {
      EXPECT_EQ(png.status, 0);
    }
    std::filesystem::remove(path);
    for (const char* suffix : {"-1.png", "-01.png"}) std::filesystem::remove(path + suffix);
  }
}

TEST(Pdf, ThePageLineFitsNarrowPaper) {
  // An octahedron 400 mm across tiled on 50 x 50 mm paper: dozens of pages, each with its line
  // "page k of n (row r, column c)", which at the usual size ran past both edges of the page.
  const Mesh mesh = test::octahedron(-0.4);
  PrintOptions print;
  print.size_mm = 400;
  PrintLayout layout = layout_net(mesh, test::bfs_net(mesh), print);
  PageOptions o;
  o.paper = parse_paper("50x50mm");
  const PageLayout pages = paginate(layout, o);
  ASSERT_GT(pages.pages.size(), 10u);
  const std::string path = temp_path("narrow.pdf");
  std::ofstream(path, std::ios::binary) << write_pdf(layout, pages);
  const int last = static_cast<int>(pages.pages.size());
  const ToolRun text = run("pdftotext", "-bbox -f " + std::to_string(last) + " -l " +
                                            std::to_string(last) + " " + path + " -");
  std::filesystem::remove(path);
  if (!text.present) GTEST_SKIP() << "pdftotext missing: install poppler-utils";
  ASSERT_EQ(text.status, 0) << text.out;
  // The words of the last page, the line's among them, from where the PDF draws them.
  const double width = 50 / 25.4 * 72;  // points
  int words = 0;
  bool named = false;
  for (std::size_t at = text.out.find("<word"); at != std::string::npos;
       at = text.out.find("<word", at + 1)) {
    const auto attribute = [&](const std::string& name) {
      return std::stod(text.out.substr(text.out.find(name + "=\"", at) + name.size() + 2));
    };
    EXPECT_GE(attribute("xMin"), 0);
    EXPECT_LE(attribute("xMax"), width);
    const std::size_t open = text.out.find('>', at) + 1;
    named = named || text.out.substr(open, text.out.find('<', open) - open) == "column";
    ++words;
  }
  EXPECT_TRUE(named) << text.out;
  EXPECT_GT(words, 0);
}

// Pixels of an RGB image (PPM, "P6") whose colour is within 40 of `rgb` in each channel.
int pixels_near(const std::string& ppm, unsigned rgb) {
  std::istringstream in(ppm);
  std::string magic;
  int w = 0, h = 0, most = 0;
  in >> magic >> w >> h >> most;
  in.get();
  if (magic != "P6" || most != 255) return -1;
  int n = 0;
  for (int i = 0; i < w * h; ++i) {
    const int r = in.get(), g = in.get(), b = in.get();
    if (!in) return -1;
    n += std::abs(r - int((rgb >> 16) & 255)) < 40 && std::abs(g - int((rgb >> 8) & 255)) < 40 &&
         std::abs(b - int(rgb & 255)) < 40;
  }
  return n;
}

// Every page carries the key to its lines in its top margin: a sample of the cut, the mountain
// fold and the valley fold, each drawn as the net's lines of its kind are, beside its name; read
// from the drawing, the SVG, and the PDF's words and pixels. Tiled pages keep it clear of the
// overlap ticks; paper or margins too small for it leave it out.
TEST(Pdf, EveryPageHasTheKeyToItsLines) {
  PrintOptions print;
  print.size_mm = 250;
  // A part of tests/data with folds of both kinds, 600 faces.
  const Mesh mesh = load_mesh_file(test::test_data_dir() + "/trimesh_ADIS16480_600.obj").mesh;
  PrintLayout layout = layout_net(mesh, test::bfs_net(mesh), print);
  ASSERT_FALSE(layout.mountain.empty());
  ASSERT_FALSE(layout.valley.empty());
  const PageLayout pages = paginate(layout, {});  // A4, 10 mm margins, tiled
  ASSERT_GT(pages.pages.size(), 1u);
  const double m = pages.margin, ov = pages.overlap;
  for (int k = 0; k < static_cast<int>(pages.pages.size()); ++k) {
    SCOPED_TRACE("page " + std::to_string(k + 1));
    const PageDrawing d = draw_page(layout, pages, k);
    std::vector<const Shape*> lines, names;
    for (const Shape& s : d.shapes) {
      if (s.key) lines.push_back(&s);
      if (s.layer == Layer::Marks && !s.text.empty() && s.points[0].y < m) names.push_back(&s);
    }
    ASSERT_EQ(lines.size(), 3u);
    ASSERT_EQ(names.size(), 3u);
    const char* expected[] = {"cut", "mountain fold", "valley fold"};
    const Layer layers[] = {Layer::Cut, Layer::Mountain, Layer::Valley};
    for (std::size_t i = 0; i < 3; ++i) {
      const Shape& line = *lines[i];
      const Shape& name = *names[i];
      EXPECT_EQ(line.layer, layers[i]);
      EXPECT_EQ(name.text, expected[i]);
      ASSERT_EQ(line.points.size(), 2u);
      const double left = line.points[0].x, right = line.points[1].x;
      EXPECT_GE(right - left, 8 - 1e-9) << "a sample shows at least two periods of its dashes";
      // In the top margin, clear of the overlap ticks (at m + ov and width - m - ov).
      for (const Vec2 p : line.points) {
        EXPECT_GT(p.y, 0);
        EXPECT_LT(p.y + 0.5 * name.size, m);
      }
      const double name_left = name.points[0].x - 0.5 * text_width(name.text, name.size);
      const double name_right = name.points[0].x + 0.5 * text_width(name.text, name.size);
      EXPECT_GT(left, m + ov);
      EXPECT_LT(name_right, pages.width - m - ov);
      EXPECT_GT(name_left, right) << "the name follows its sample";
      if (i + 1 < 3) {
        EXPECT_LT(name_right, lines[i + 1]->points[0].x) << "apart from the next entry";
      }
    }
    // The SVG draws the samples unclipped, each in its layer's style.
    const std::string svg = write_page_svg(layout, d, k, static_cast<int>(pages.pages.size()));
    const auto key_at = svg.find("<g id=\"key\">");
    ASSERT_NE(key_at, std::string::npos);
    const std::string key = svg.substr(key_at, svg.find("</g>", key_at) - key_at);
    EXPECT_EQ(key.find("clip-path"), std::string::npos);
    EXPECT_NE(key.find("stroke=\"#000000\" stroke-width=\"0.25\""), std::string::npos);
    EXPECT_NE(key.find("stroke-dasharray=\"2 1\""), std::string::npos);
    EXPECT_NE(key.find("stroke-dasharray=\"2 0.7 0.4 0.7\""), std::string::npos);
  }

  // The PDF: the names on every page above the printable area, the samples' red and blue there.
  const std::string path = temp_path("key.pdf");
  std::ofstream(path, std::ios::binary) << write_pdf(layout, pages);
  const ToolRun text = run("pdftotext", "-bbox " + path + " -");
  if (!text.present) GTEST_SKIP() << "pdftotext missing: install poppler-utils";
  ASSERT_EQ(text.status, 0) << text.out;
  const double points = 72 / 25.4;
  int pages_read = 0;
  for (std::size_t at = text.out.find("<page"); at != std::string::npos;
       at = text.out.find("<page", at + 1)) {
    const std::size_t end = text.out.find("</page>", at);
    std::set<std::string> above;  // the words wholly within the top margin
    for (std::size_t w = text.out.find("<word", at); w < end; w = text.out.find("<word", w + 1)) {
      const auto attribute = [&](const std::string& name) {
        return std::stod(text.out.substr(text.out.find(name + "=\"", w) + name.size() + 2));
      };
      const std::size_t open = text.out.find('>', w) + 1;
      if (attribute("yMax") < m * points)
        above.insert(text.out.substr(open, text.out.find('<', open) - open));
    }
    // (pdftotext reads the labels the page clips away too: only the key's words are looked for.)
    for (const char* word : {"cut", "mountain", "valley", "fold"})
      EXPECT_EQ(above.count(word), 1u) << "page " << pages_read + 1 << ": " << word;
    ++pages_read;
  }
  EXPECT_EQ(pages_read, static_cast<int>(pages.pages.size()));
  // The top margin of page 1 at 150 dpi: the mountain sample's red, the valley's blue.
  const int margin_px = static_cast<int>(m / 25.4 * 150);
  const ToolRun top = run("pdftoppm", "-r 150 -f 1 -l 1 -y 0 -H " + std::to_string(margin_px) +
                                          " -W 1240 -x 0 " + path);
  std::filesystem::remove(path);
  if (!top.present) GTEST_SKIP() << "pdftoppm missing: install poppler-utils";
  ASSERT_EQ(top.status, 0);
  EXPECT_GT(pixels_near(top.out, 0xc0392b), 20);
  EXPECT_GT(pixels_near(top.out, 0x1f5fbf), 20);

  // No key where there is no room: 50 mm paper, or margins of 4 mm.
  PageOptions narrow;
  narrow.paper = parse_paper("50x50mm");
  PageOptions thin;
  thin.margin_mm = 4;
  PrintOptions small_print;
  small_print.size_mm = 100;
  for (const PageOptions& o : {narrow, thin}) {
    PrintLayout again = layout_net(mesh, test::bfs_net(mesh), small_print);
    const PageLayout small = paginate(again, o);
    ASSERT_FALSE(small.pages.empty());
    for (int k = 0; k < std::min<int>(4, static_cast<int>(small.pages.size())); ++k)
      for (const Shape& s : draw_page(again, small, k).shapes) {
        EXPECT_FALSE(s.key);
        if (s.layer == Layer::Marks && !s.text.empty()) {
          EXPECT_EQ(s.text.rfind("page ", 0), 0u) << s.text;
        }
      }
  }
}

// Text that starts at its point (the build order's lines) is drawn from there in the PDF and the
// SVG, where other text is centred on it: two lines of different lengths starting at x = 30 mm
// begin at the same place in the PDF (pdftotext's boxes), and centred ones do not.
TEST(Pdf, TextThatStartsAtItsPointIsDrawnFromThere) {
  PageDrawing d{210, 297, {10, 10}, {200, 287}, {}, {}, {}};
  const char* lines[] = {"P3 glues to P1, P2", "P4 glues to P1, P2, P3, P17, P21"};
  for (int i = 0; i < 2; ++i) {
    Shape start{Layer::Labels, {{30, 50.0 + 10 * i}}, false, lines[i], 3, 0};
    start.start = true;
    d.shapes.push_back(start);
    d.shapes.push_back({Layer::Labels, {{105, 100.0 + 10 * i}}, false, lines[i], 3, 0});
  }
  const std::string svg = write_svg(d, {});
  EXPECT_EQ(count_of(svg, "text-anchor=\"start\""), 2);
  PrintLayout layout;
  PdfWriter writer(layout, 210, 297);
  writer.add_page(d);
  const std::string path = temp_path("start.pdf");
  std::ofstream(path, std::ios::binary) << writer.finish();
  const ToolRun text = run("pdftotext", "-bbox " + path + " -");
  std::filesystem::remove(path);
  if (!text.present) GTEST_SKIP() << "pdftotext missing: install poppler-utils";
  ASSERT_EQ(text.status, 0) << text.out;
  // The left end of each line's first word ("P3", "P4"), by the line's height on the page.
  std::map<long, double> left;  // yMin in points -> xMin in mm
  for (std::size_t at = text.out.find("<word"); at != std::string::npos;
       at = text.out.find("<word", at + 1)) {
    const auto attribute = [&](const std::string& name) {
      return std::stod(text.out.substr(text.out.find(name + "=\"", at) + name.size() + 2));
    };
    const long y = std::lround(attribute("yMin"));
    if (!left.count(y)) left[y] = attribute("xMin") * 25.4 / 72;
  }
  ASSERT_EQ(left.size(), 4u) << text.out;
  std::vector<double> x;
  for (const auto& [y, at] : left) x.push_back(at);
  EXPECT_NEAR(x[0], 30, 0.5);  // the lines that start at 30 mm
  EXPECT_NEAR(x[1], 30, 0.5);
  EXPECT_GT(x[2] - x[3], 5) << "centred lines of different lengths start apart";
}

}  // namespace
}  // namespace papernet
