// The overview of a print of many sheets and pieces (print/overview.h): when its sheets and
// build order do not fit one page legibly, it goes on over more pages, and together they still
// list every piece once with its sheet and every step of the build order once, all of it inside
// the printable area, no text over another, on any paper that holds it; paper too small for it
// leaves it out.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "print/overview.h"
#include "print/svg.h"

namespace papernet::test {
namespace {

/// Paper of `width` x `height` mm with `margin` mm margins.
struct Sheet {
  double width = 210, height = 297, margin = 10;
};

/// `sheets` sheets of `paper` holding `pieces` pieces of one triangle each, in order; each piece
/// glues to the `joins` pieces before it (long lines in the build order).
struct Print {
  PrintLayout layout;
  PageLayout pages;
  std::vector<int> piece;
  PieceGraph graph;
};

Print print_of(int sheets, int pieces, int joins, Sheet paper = {}) {
  Print p;
  p.pages.width = paper.width;
  p.pages.height = paper.height;
  p.pages.margin = paper.margin;
  p.pages.fitted = true;
  const double w = paper.width - 2 * paper.margin, h = paper.height - 2 * paper.margin;
  const double apart = w + 100;  // the sheets' distance in the layout
  for (int s = 0; s < sheets; ++s) {
    Page page;
    page.col = s;
    page.lo = {apart * s, 0};
    page.hi = {apart * s + w, h};
    p.pages.pages.push_back(page);
  }
  p.graph.joins.resize(static_cast<std::size_t>(pieces));
  for (int k = 0; k < pieces; ++k) {
    const int s = k * sheets / pieces;
    const Vec2 at{apart * s + w * (0.05 + 0.2 * (k % 4)), h * (0.07 + 0.14 * (k % 6))};
    const double side = 0.15 * std::min(w, h);
    p.layout.faces.push_back({at, at + Vec2{side, 0}, at + Vec2{0, side}});
    p.piece.push_back(k);
    Label number;
    number.at = at + Vec2{0.25 * side, 0.25 * side};
    number.size = 4;
    number.text = piece_name(k);
    p.layout.piece_labels.push_back(number);
    for (int j = 1; j <= joins && k - j >= 0; ++j) {
      p.graph.joins[k].push_back(k - j);
      p.graph.joins[k - j].push_back(k);
    }
  }
  return p;
}

struct Text {
  double x0, y0, x1, y1;
  std::string text;
  double size = 0;
};

/// The texts of a drawing with their boxes (0.6 of the size a character wide, 0.7 high): centred
/// on their point, or starting at it.
std::vector<Text> texts(const PageDrawing& d) {
  std::vector<Text> out;
  for (const Shape& s : d.shapes) {
    if (s.text.empty()) continue;
    const double w = 0.6 * s.size * label_chars(s.text), h = 0.35 * s.size;
    const double x0 = s.start ? s.points[0].x : s.points[0].x - 0.5 * w;
    out.push_back({x0, s.points[0].y - h, x0 + w, s.points[0].y + h, s.text, s.size});
  }
  return out;
}

/// The number of overview pages at the start of `pages`.
int overview_pages_of(const PageLayout& pages) {
  int n = 0;
  while (n < static_cast<int>(pages.pages.size()) && pages.pages[n].overview) ++n;
  return n;
}

/// Checks the overview of `p` (`sheets` sheets, `pieces` pieces): every text inside the
/// printable area, 2 mm high or more, none over another; each piece listed once with its sheet,
/// each step of the build order once.
void check_overview(const Print& p, const Sheet& paper, int sheets, int pieces) {
  const int overview_pages = overview_pages_of(p.pages);
  ASSERT_EQ(static_cast<int>(p.pages.pages.size()), sheets + overview_pages);
  const double m = paper.margin;
  std::map<int, int> listed;  // piece -> the page its caption names
  std::set<int> steps;
  static const std::regex caption("^page (\\d+):(.*)$"), name("P(\\d+)"),
      step("^P(\\d+)( glues to .*|: start here)$");
  for (int k = 0; k < overview_pages; ++k) {
    const PageDrawing d = draw_overview(p.layout, p.pages, k);
    const std::vector<Text> all = texts(d);
    int page = -1;
    bool more = false;
    for (const Text& t : all) {
      EXPECT_GE(t.x0, m - 1e-6) << t.text;
      EXPECT_LE(t.x1, paper.width - m + 1e-6) << t.text;
      EXPECT_GE(t.y0, m - 1e-6) << t.text;
      EXPECT_LE(t.y1, paper.height - m + 1e-6) << t.text << " on overview page " << k + 1;
      EXPECT_GE(t.y1 - t.y0, 0.7 * 2 - 1e-6) << t.text << ": 2 mm or more";
      std::smatch match;
      if (more || std::regex_match(t.text, match, caption)) {
        if (!more) page = std::stoi(match[1]) - 1;
        const std::string rest = more ? t.text : std::string(match[2]);
        for (auto it = std::sregex_iterator(rest.begin(), rest.end(), name);
             it != std::sregex_iterator(); ++it)
          EXPECT_TRUE(listed.emplace(std::stoi((*it)[1]) - 1, page).second) << (*it)[0];
        more = !rest.empty() && rest.back() == ',';
      } else if (std::regex_match(t.text, match, step)) {
        EXPECT_TRUE(steps.insert(std::stoi(match[1]) - 1).second) << t.text;
      }
    }
    for (std::size_t a = 0; a < all.size(); ++a)
      for (std::size_t b = a + 1; b < all.size(); ++b)
        EXPECT_FALSE(all[a].x0 < all[b].x1 && all[b].x0 < all[a].x1 && all[a].y0 < all[b].y1 &&
                     all[b].y0 < all[a].y1)
            << "\"" << all[a].text << "\" covers \"" << all[b].text << "\"";
  }
  ASSERT_EQ(static_cast<int>(listed.size()), pieces) << "each piece listed once";
  for (const auto& [piece, page] : listed)
    EXPECT_EQ(page, overview_pages + piece * sheets / pieces) << "P" << piece + 1;
  EXPECT_EQ(static_cast<int>(steps.size()), pieces) << "each piece's build step once";
}

TEST(Overview, ManySheetsAndPiecesGoOnOverMorePagesListingEachOnce) {
  for (const auto& [sheets, pieces, joins] : {std::array{3, 12, 2}, std::array{72, 448, 8}}) {
    SCOPED_TRACE(std::to_string(pieces) + " pieces on " + std::to_string(sheets) + " sheets");
    Print p = print_of(sheets, pieces, joins);
    ASSERT_TRUE(add_overview(p.pages, p.layout, p.piece, p.graph));
    const int overview_pages = overview_pages_of(p.pages);
    if (sheets == 3) {
      EXPECT_EQ(overview_pages, 1) << "a small print's overview is one page";
    } else {
      EXPECT_GT(overview_pages, 1) << "448 pieces on 72 sheets do not fit one page";
    }
    check_overview(p, {}, sheets, pieces);
  }
}

// An overview of several pages whose last page would hold a few lines of the build order alone
// prints smaller, on a page fewer: 30 pieces on 11 sheets of A5 (as the Duck prints there) took
// three pages at 32 mm thumbnails and 2.5 mm text, the third for 14 lines; now two, at 2 mm.
TEST(Overview, PrintsSmallerWhereThatSavesAPage) {
  const Sheet a5{148, 210, 10};
  Print p = print_of(11, 30, 3, a5);
  ASSERT_TRUE(add_overview(p.pages, p.layout, p.piece, p.graph));
  check_overview(p, a5, 11, 30);
  ASSERT_EQ(overview_pages_of(p.pages), 2);
  for (int k = 0; k < 2; ++k)
    for (const Text& t : texts(draw_overview(p.layout, p.pages, k)))
      if (t.text.rfind("P30 glues to", 0) == 0) {
        EXPECT_DOUBLE_EQ(t.size, 2) << t.text;
      }
}

// On small paper, where a column of thumbnails holds one to a page, the overview prints them
// smaller, several rows to a page, where that takes fewer pages and leaves each piece's number
// room: 30 pieces on 13 sheets of 90 x 130 mm (as sample.obj prints there) took 8 overview
// pages, thumbnails two to a page; now 4 or more to a page after the first.
TEST(Overview, SmallPaperTakesSeveralRowsOfThumbnailsToAPage) {
  const Sheet card{90, 130, 10};
  Print p = print_of(13, 30, 3, card);
  ASSERT_TRUE(add_overview(p.pages, p.layout, p.piece, p.graph));
  check_overview(p, card, 13, 30);
  const int overview_pages = overview_pages_of(p.pages);
  static const std::regex caption("^page \\d+:.*$");
  int most = 0;  // thumbnails on a page after the first
  for (int k = 1; k < overview_pages; ++k) {
    int on_page = 0;
    for (const Text& t : texts(draw_overview(p.layout, p.pages, k)))
      on_page += std::regex_match(t.text, caption);
    most = std::max(most, on_page);
  }
  EXPECT_GE(most, 4);
  EXPECT_LE(overview_pages, 5);
  std::printf(
      "30 pieces on 13 sheets of 90 x 130 mm: %d overview pages, at most %d thumbnails "
      "to a page after the first\n",
      overview_pages, most);
}

// On an overview of several pages the build order of many pieces takes several columns, its long
// steps broken after a comma onto more lines, rather than one column as wide as its longest step
// (the Menger sponge's 448 pieces on 72 sheets at the defaults: 12 overview pages, 7 of them a
// single column of the build order; 9 now, in two columns), and no step split between two
// columns where one holds it whole. A column's steps start at one left edge, the lines that go
// on with a step indented from it (1.5 text heights), so that a broken step reads as one.
// check_overview reads each step once, every text apart.
TEST(Overview, TheBuildOrderOfManyPiecesTakesSeveralColumns) {
  Print p = print_of(72, 448, 8);
  ASSERT_TRUE(add_overview(p.pages, p.layout, p.piece, p.graph));
  check_overview(p, {}, 72, 448);
  const int overview_pages = overview_pages_of(p.pages);
  static const std::regex step("^P\\d+ glues to .*,$"),  // a step broken onto the next line
      head("^P\\d+( glues to |: start ).*$");
  std::size_t broken = 0;
  for (int k = 0; k < overview_pages; ++k) {
    const std::vector<Text> all = texts(draw_overview(p.layout, p.pages, k));
    // The build order's lines: below its heading.
    double below = -1;
    for (const Text& t : all)
      if (t.text.rfind("Build order", 0) == 0) below = t.y1;
    if (below < 0) continue;
    // The columns: the left edges of the steps' first lines (to a hundredth of a millimetre),
    // each with its top line; every line starts at one, or 1.5 text heights right of one.
    std::map<long, const Text*> columns;
    for (const Text& t : all)
      if (t.y0 >= below && std::regex_match(t.text, head)) columns[std::lround(100 * t.x0)] = &t;
    for (const Text& t : all) {
      if (t.y0 < below) continue;
      const bool first = std::regex_match(t.text, head);
      const long edge = std::lround(100 * (first ? t.x0 : t.x0 - 1.5 * t.size));
      ASSERT_EQ(columns.count(edge), 1u)
          << "\"" << t.text << "\" on overview page " << k + 1 << " starts at no column's edge"
          << (first ? "" : " less the indent");
      const Text*& top = columns[edge];
      if (t.y0 < top->y0) top = &t;
      broken += std::regex_match(t.text, step);
    }
    if (k + 1 < overview_pages) {
      EXPECT_GE(columns.size(), 2u) << "overview page " << k + 1 << ": one column";
    }
    // A step a column holds whole is not split between two: each column begins with one.
    for (const auto& [centre, top] : columns)
      EXPECT_TRUE(std::regex_match(top->text, head))
          << "overview page " << k + 1 << ": a column begins with \"" << top->text << "\"";
  }
  EXPECT_GT(broken, 0u) << "no long step broken: the test's steps are too short to tell";
  std::printf("448 pieces on 72 sheets: %d overview pages, %zu steps broken\n", overview_pages,
              broken);
}

// On small paper the header breaks into lines that fit, and everything stays inside the
// printable area: A5, A6, 100 x 100 mm and a strip 70 mm wide.
TEST(Overview, SmallPaperHoldsTheOverviewWithinItsMargins) {
  for (const Sheet paper :
       {Sheet{148, 210, 10}, Sheet{105, 148, 10}, Sheet{100, 100, 10}, Sheet{70, 300, 10}})
    for (const auto& [sheets, pieces, joins] : {std::array{3, 12, 2}, std::array{20, 60, 3}}) {
      SCOPED_TRACE(std::to_string(paper.width) + " x " + std::to_string(paper.height) + " mm, " +
                   std::to_string(pieces) + " pieces on " + std::to_string(sheets) + " sheets");
      Print p = print_of(sheets, pieces, joins, paper);
      ASSERT_TRUE(add_overview(p.pages, p.layout, p.piece, p.graph));
      check_overview(p, paper, sheets, pieces);
    }
}

// A kit with a title names every page with it ("Duck \u00b7 page 2 of 4") and titles the
// overview with it; a title with a word wider than the page leaves the overview its own title,
// the page lines still naming the kit within the page's width.
TEST(Overview, TheKitsTitleNamesTheOverviewAndEveryPage) {
  const std::string long_word(80, 'W');
  struct Case {
    std::string title;
    Sheet paper;
    std::string heading;  // the overview's title
  };
  for (const Case& c : {Case{"Duck", Sheet{}, "Duck: 12 pieces on 3 sheets"},
                        Case{long_word, Sheet{148, 210, 10}, "Overview: 12 pieces on 3 sheets"}}) {
    const std::string &title = c.title, &heading = c.heading;
    const Sheet paper = c.paper;
    SCOPED_TRACE(title);
    Print p = print_of(3, 12, 2, paper);
    p.pages.title = title;
    ASSERT_TRUE(add_overview(p.pages, p.layout, p.piece, p.graph));
    check_overview(p, paper, 3, 12);
    const int n = static_cast<int>(p.pages.pages.size());
    ASSERT_EQ(n, 4);
    for (int k = 0; k < n; ++k) {
      const std::vector<Text> all = texts(draw_page(p.layout, p.pages, k));
      const std::string line =
          title + " \u00b7 page " + std::to_string(k + 1) + " of 4" + (k == 0 ? ": overview" : "");
      const auto found =
          std::find_if(all.begin(), all.end(), [&](const Text& t) { return t.text == line; });
      ASSERT_NE(found, all.end()) << line;
      EXPECT_GE(found->x0, 0);
      EXPECT_LE(found->x1, paper.width);
      EXPECT_NE(write_page_svg(p.layout, draw_page(p.layout, p.pages, k), k, n)
                    .find("<title>" + line + "</title>"),
                std::string::npos)
          << line;
      if (k == 0) {
        EXPECT_TRUE(std::any_of(all.begin(), all.end(), [&](const Text& t) {
          return t.text == heading;
        })) << heading;
      }
    }
  }
}

// On paper far larger than A3 (3 x 3 m, a plotter's) the thumbnails stay at most 250 mm long,
// where they grew with the page (the views of the model beside them were painted 1.4 m large).
TEST(Overview, LargePaperKeepsItsThumbnailsSmall) {
  const Sheet paper{3000, 3000, 10};
  Print p = print_of(3, 12, 2, paper);
  ASSERT_TRUE(add_overview(p.pages, p.layout, p.piece, p.graph));
  check_overview(p, paper, 3, 12);
  const PageDrawing d = draw_overview(p.layout, p.pages, 0);
  double longest = 0;  // of the dashed sides of the thumbnails' printable areas
  int sides = 0;
  for (const Shape& s : d.shapes)
    if (s.layer == Layer::Marks && s.points.size() == 2 && s.text.empty()) {
      longest = std::max(longest, norm(s.points[1] - s.points[0]));
      ++sides;
    }
  EXPECT_GE(sides, 12) << "four sides of each of the 3 thumbnails";
  EXPECT_NEAR(longest, 250, 1e-6);
}

// Paper too small for a legible overview (its header's words wider than the printable area, or
// too little room below the header) leaves it out, the pages as they were; it once planned
// overview pages without end (papernet unfold --paper 40x40mm ran out of memory).
TEST(Overview, PaperTooSmallForItLeavesItOut) {
  for (const Sheet paper : {Sheet{40, 40, 10}, Sheet{30, 30, 5}, Sheet{25, 300, 2},
                            Sheet{300, 40, 10}, Sheet{80, 80, 10}, Sheet{50, 300, 10}})
    for (const auto& [sheets, pieces, joins] : {std::array{1, 2, 1}, std::array{20, 60, 3}}) {
      SCOPED_TRACE(std::to_string(paper.width) + " x " + std::to_string(paper.height) + " mm, " +
                   std::to_string(pieces) + " pieces on " + std::to_string(sheets) + " sheets");
      Print p = print_of(sheets, pieces, joins, paper);
      EXPECT_FALSE(add_overview(p.pages, p.layout, p.piece, p.graph));
      EXPECT_EQ(overview_pages_of(p.pages), 0);
      EXPECT_EQ(static_cast<int>(p.pages.pages.size()), sheets);
      EXPECT_FALSE(p.pages.overview);
    }
}

}  // namespace
}  // namespace papernet::test
