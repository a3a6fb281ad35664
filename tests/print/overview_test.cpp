// The overview of a print of many sheets and pieces (print/overview.h): when its sheets and
// build order do not fit one page legibly, it goes on over more pages, and together they still
// list every piece once with its sheet and every step of the build order once, all of it inside
// the printable area, no text over another.
#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "print/overview.h"

namespace papernet::test {
namespace {

/// `sheets` A4 sheets (10 mm margins) holding `pieces` pieces of one triangle each, in order;
/// each piece glues to the `joins` pieces before it (long lines in the build order).
struct Print {
  PrintLayout layout;
  PageLayout pages;
  std::vector<int> piece;
  PieceGraph graph;
};

Print print_of(int sheets, int pieces, int joins) {
  Print p;
  p.pages.width = 210;
  p.pages.height = 297;
  p.pages.margin = 10;
  p.pages.fitted = true;
  for (int s = 0; s < sheets; ++s) {
    Page page;
    page.col = s;
    page.lo = {300.0 * s, 0};
    page.hi = {300.0 * s + 190, 277};
    p.pages.pages.push_back(page);
  }
  p.graph.joins.resize(static_cast<std::size_t>(pieces));
  for (int k = 0; k < pieces; ++k) {
    const int s = k * sheets / pieces;
    const Vec2 at{300.0 * s + 10 + 40 * (k % 4), 20 + 40.0 * (k % 6)};
    p.layout.faces.push_back({at, at + Vec2{30, 0}, at + Vec2{0, 30}});
    p.piece.push_back(k);
    Label number;
    number.at = at + Vec2{8, 8};
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
};

/// The texts of a drawing with their boxes (0.6 of the size a character wide, 0.7 high).
std::vector<Text> texts(const PageDrawing& d) {
  std::vector<Text> out;
  for (const Shape& s : d.shapes) {
    if (s.text.empty()) continue;
    const double w = 0.5 * 0.6 * s.size * label_chars(s.text), h = 0.35 * s.size;
    out.push_back(
        {s.points[0].x - w, s.points[0].y - h, s.points[0].x + w, s.points[0].y + h, s.text});
  }
  return out;
}

TEST(Overview, ManySheetsAndPiecesGoOnOverMorePagesListingEachOnce) {
  for (const auto& [sheets, pieces, joins] : {std::array{3, 12, 2}, std::array{72, 448, 8}}) {
    Print p = print_of(sheets, pieces, joins);
    add_overview(p.pages, p.layout, p.piece, p.graph);
    int overview_pages = 0;
    while (overview_pages < static_cast<int>(p.pages.pages.size()) &&
           p.pages.pages[overview_pages].overview)
      ++overview_pages;
    ASSERT_EQ(static_cast<int>(p.pages.pages.size()), sheets + overview_pages);
    if (sheets == 3) {
      EXPECT_EQ(overview_pages, 1) << "a small print's overview is one page";
    } else {
      EXPECT_GT(overview_pages, 1) << "448 pieces on 72 sheets do not fit one page";
    }
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
        EXPECT_GE(t.x0, 10 - 1e-6) << t.text;
        EXPECT_LE(t.x1, 200 + 1e-6) << t.text;
        EXPECT_GE(t.y0, 10 - 1e-6) << t.text;
        EXPECT_LE(t.y1, 287 + 1e-6) << t.text << " on overview page " << k + 1;
        EXPECT_GE(t.y1 - t.y0, 0.7 * 2 - 1e-6) << t.text << ": 2 mm or more";
        std::smatch m;
        if (more || std::regex_match(t.text, m, caption)) {
          if (!more) page = std::stoi(m[1]) - 1;
          const std::string rest = more ? t.text : std::string(m[2]);
          for (auto it = std::sregex_iterator(rest.begin(), rest.end(), name);
               it != std::sregex_iterator(); ++it)
            EXPECT_TRUE(listed.emplace(std::stoi((*it)[1]) - 1, page).second) << (*it)[0];
          more = !rest.empty() && rest.back() == ',';
        } else if (std::regex_match(t.text, m, step)) {
          EXPECT_TRUE(steps.insert(std::stoi(m[1]) - 1).second) << t.text;
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
}

}  // namespace
}  // namespace papernet::test
