// Assembly aids (docs/print.md, "Build order" and "The overview page"), on the Duck (and a CAD
// part of many small pieces) at the defaults (detail auto, 200 mm, A4, layout fit): pieces
// numbered so that each glues to one before it, labels across pieces naming the piece they join,
// and the overview page listing every piece with its sheet. Checked against an adjacency built
// here from the net JSON's mesh and pieces, and against the drawn pages, not against the print's
// own data.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <optional>
#include <regex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "api/net_json.h"
#include "core/unfold/net_check.h"
#include "engine/pipeline.h"
#include "tests/support/job_input.h"
#include "tests/support/paths.h"
#include "tests/support/polygons.h"
#include "tests/support/sanitized.h"
#include "tests/support/svg.h"

namespace papernet::test {
namespace {

struct Printed {
  NetDocument doc;
  std::vector<std::string> pages;  ///< each page's SVG
  std::string pdf;
};

const Printed& duck() {
  static const Printed printed = [] {
    JobOptions options;
    options.layout = PageLayoutMode::Fit;
    options.colour = false;  // the assembly aids are line art; colour is colour_print_test's
    lighten(options);
    PipelineProgress quiet;
    UnfoldOutcome out =
        run_pipeline(data_file("Duck.glb"), options, {}, {.svg_pages = true, .pdf = true}, quiet);
    return Printed{read_net_json(out.documents.net_json), out.documents.svg_pages,
                   out.documents.pdf};
  }();
  return printed;
}

/// A file of tests/data printed in line art with `options` (layout fit), its SVG pages.
Printed line_art(const std::string& file, JobOptions options = {}) {
  options.layout = PageLayoutMode::Fit;
  options.colour = false;
  lighten(options);
  PipelineProgress quiet;
  UnfoldOutcome out = run_pipeline(data_file(file), options, {}, {.svg_pages = true}, quiet);
  return Printed{read_net_json(out.documents.net_json), out.documents.svg_pages, {}};
}

/// A CAD part of small features, many short cut edges and small pieces, at the defaults.
const Printed& cad_part() {
  static const Printed printed = line_art("trimesh_ADIS16480_600.obj");
  return printed;
}

/// The edge labels drawn on the sheets (the overview's text aside): each one's text and size, mm.
std::vector<std::pair<std::string, double>> sheet_labels(const Printed& printed) {
  static const std::regex label("font-size=\"([0-9.]+)\"[^>]*>([^<]+)</text>");
  std::vector<std::pair<std::string, double>> out;
  for (std::size_t k = 0; k < printed.pages.size(); ++k) {
    if (printed.doc.print && static_cast<int>(k) == printed.doc.print->overview_page) continue;
    const std::string g = svg_group(printed.pages[k], "labels");
    for (auto it = std::sregex_iterator(g.begin(), g.end(), label); it != std::sregex_iterator();
         ++it)
      out.emplace_back((*it)[2].str(), std::stod((*it)[1]));
  }
  return out;
}

/// Those of sheet_labels under 1.5 mm.
std::vector<std::pair<std::string, double>> small_labels(const Printed& printed) {
  std::vector<std::pair<std::string, double>> out = sheet_labels(printed);
  std::erase_if(out, [](const auto& label) { return label.second >= 1.5 - 1e-3; });
  return out;
}

/// Which pieces share a mesh edge, from the mesh's faces (edges by their two vertices) and each
/// face's piece; `cross_edges` counts the edges between different pieces.
struct Adjacency {
  std::vector<std::set<int>> joins;
  std::size_t cross_edges = 0;
};

Adjacency adjacency(const NetDocument& doc) {
  std::map<std::pair<int, int>, std::vector<int>> faces_of_edge;
  for (std::size_t f = 0; f < doc.mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = doc.mesh.faces[f][k], b = doc.mesh.faces[f][(k + 1) % 3];
      faces_of_edge[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  Adjacency out;
  out.joins.resize(doc.pieces.size());
  for (const auto& [edge, faces] : faces_of_edge) {
    if (faces.size() != 2) continue;
    const int p = doc.piece[faces[0]], q = doc.piece[faces[1]];
    if (p == q) continue;
    out.joins[p].insert(q);
    out.joins[q].insert(p);
    ++out.cross_edges;
  }
  return out;
}

/// The texts of one SVG group, in order.
std::vector<std::string> texts(const std::string& svg, const std::string& group) {
  std::vector<std::string> out;
  const std::string g = svg_group(svg, group);
  static const std::regex text("<text [^>]*>([^<]*)</text>");
  for (auto it = std::sregex_iterator(g.begin(), g.end(), text); it != std::sregex_iterator(); ++it)
    out.push_back((*it)[1].str());
  return out;
}

/// The texts of an overview page outside its views of the model (its <image>s), in order.
std::vector<std::string> overview_texts(const std::string& page) {
  const std::vector<SvgBox> views = svg_images(page);
  std::vector<std::string> out;
  for (const SvgText& t : svg_texts(svg_group(page, "labels")))
    if (std::none_of(views.begin(), views.end(),
                     [&](const SvgBox& v) { return v.holds(t.x, t.y - 0.35 * t.size); }))
      out.push_back(t.text);
  return out;
}

TEST(AssemblyAids, TheNetAsPrintedPassesTheNetChecker) {
  const NetDocument& doc = duck().doc;
  ASSERT_TRUE(doc.print);
  const NetCheckReport check = check_pieces(doc.mesh, doc.net, doc.piece);
  EXPECT_TRUE(check.ok()) << check.summary();
}

// Piece k glues to a piece before it whenever any piece not yet numbered does.
TEST(AssemblyAids, EachPieceGluesToAnEarlierOneWheneverTheGraphAllows) {
  const NetDocument& doc = duck().doc;
  const Adjacency adj = adjacency(doc);
  const int n = static_cast<int>(doc.pieces.size());
  ASSERT_GT(n, 2) << "the Duck should print as several pieces";
  std::size_t glued = 0;
  for (int k = 1; k < n; ++k) {
    auto earlier = [&](int p) {
      return std::any_of(adj.joins[p].begin(), adj.joins[p].end(), [k](int q) { return q < k; });
    };
    bool possible = false;
    for (int p = k; p < n; ++p) possible = possible || earlier(p);
    if (possible) {
      EXPECT_TRUE(earlier(k)) << "piece " << k << " glues to no earlier piece";
      ++glued;
    }
  }
  EXPECT_EQ(glued, static_cast<std::size_t>(n - 1)) << "the Duck is one part: all glue on";
}

// Every cut edge between two pieces has its number on both sides, each naming the other side's
// piece ("12→P3"), on the page of its own piece, but for at most `max_shortened` edges with one
// side the plain number (where the name would print under 1.5 mm, or crowd out a label that
// does not) and `max_unnamed` with both (where both sides' names would print under 1.5 mm);
// each piece's number prints once, on its page.
void expect_labels_name_the_pieces_they_join(const Printed& printed, std::size_t max_shortened,
                                             std::size_t max_unnamed) {
  const NetDocument& doc = printed.doc;
  ASSERT_TRUE(doc.print);
  const Adjacency adj = adjacency(doc);
  static const std::regex across("^(\\d+)\u2192P(\\d+)$"), plain("^(\\d+)\\.?$"),
      piece_number("^P(\\d+)$");
  std::map<int, std::vector<std::pair<int, int>>> by_number;  // number -> (page, piece named)
  std::set<int> plain_numbers;
  std::map<int, std::vector<int>> piece_pages;  // piece -> pages its number is on
  for (int k = 0; k < static_cast<int>(printed.pages.size()); ++k) {
    if (k == doc.print->overview_page) continue;
    for (const std::string& t : texts(printed.pages[k], "labels")) {
      std::smatch m;
      if (std::regex_match(t, m, across))
        by_number[std::stoi(m[1])].push_back({k, std::stoi(m[2]) - 1});
      else if (std::regex_match(t, m, plain))
        plain_numbers.insert(std::stoi(m[1]));
      else if (std::regex_match(t, m, piece_number))
        piece_pages[std::stoi(m[1]) - 1].push_back(k);
      else
        ADD_FAILURE() << "label '" << t << "' on page " << k + 1;
    }
  }
  EXPECT_LE(by_number.size(), adj.cross_edges);
  EXPECT_GE(by_number.size() + max_unnamed, adj.cross_edges)
      << "edges between pieces with named labels";
  std::size_t shortened = 0;
  for (const auto& [number, sides] : by_number) {
    ASSERT_LE(sides.size(), 2u) << "edge " << number;
    if (sides.size() == 1) {
      // A label that would print under 1.5 mm naming the piece is the plain number; its twin
      // names the piece across, from a piece on its page.
      ++shortened;
      EXPECT_EQ(plain_numbers.count(number), 1u) << "edge " << number << " has one label";
      const auto [page, b] = sides[0];
      bool beside = false;
      for (std::size_t a = 0; a < doc.pieces.size(); ++a)
        beside = beside || (doc.print->placements[a].page == page && adj.joins[a].count(b));
      EXPECT_TRUE(beside) << "edge " << number << " names P" << b + 1;
      continue;
    }
    EXPECT_EQ(plain_numbers.count(number), 0u) << "edge " << number << " also printed plain";
    const int a = sides[1].second, b = sides[0].second;  // sides[0] lies on a, names b
    ASSERT_GE(a, 0);
    ASSERT_LT(a, static_cast<int>(doc.pieces.size()));
    ASSERT_GE(b, 0);
    ASSERT_LT(b, static_cast<int>(doc.pieces.size()));
    EXPECT_NE(a, b) << "edge " << number;
    EXPECT_TRUE(adj.joins[a].count(b))
        << "edge " << number << ": P" << a + 1 << " and P" << b + 1 << " share no edge";
    EXPECT_EQ(sides[0].first, doc.print->placements[a].page) << "edge " << number;
    EXPECT_EQ(sides[1].first, doc.print->placements[b].page) << "edge " << number;
  }
  EXPECT_LE(shortened, max_shortened)
      << "of " << adj.cross_edges << " edges between pieces, shortened on one side";
  ASSERT_EQ(piece_pages.size(), doc.pieces.size());
  for (const auto& [p, pages] : piece_pages) {
    ASSERT_EQ(pages.size(), 1u) << "P" << p + 1;
    EXPECT_EQ(pages[0], doc.print->placements[p].page) << "P" << p + 1;
  }
}

TEST(AssemblyAids, EveryLabelAcrossPiecesNamesThePieceItJoins) {
  const Printed& printed = duck();
  expect_labels_name_the_pieces_they_join(
      printed, std::max<std::size_t>(1, adjacency(printed.doc).cross_edges / 60), 0);
}

// A CAD part whose small features crowd the labels of many short cut edges: the labels moved
// beside their edges around a label that found no place of 1.5 mm give up naming the piece
// across, which leaves it room (38 labels under 1.5 mm without, 32 with, since labels must
// print on their piece; docs/print.md, "Build order"), while the edges between pieces still
// name the piece on one side at least (but where both sides print under 1.5 mm: 14 of 201, at
// most 4 while labels could hang past their piece's outline).
TEST(AssemblyAids, CrowdedLabelsGiveUpThePieceNameForRoom) {
  const Printed& printed = cad_part();
  ASSERT_TRUE(printed.doc.print);
  const std::size_t cross_edges = adjacency(printed.doc).cross_edges;
  expect_labels_name_the_pieces_they_join(printed, cross_edges, cross_edges / 12);
  const auto labels = sheet_labels(printed).size();
  const auto small = small_labels(printed).size();
  EXPECT_GT(labels, 300u) << "the part no longer has many labels";
  EXPECT_LE(small, 35u) << "of " << labels << " labels, under 1.5 mm";
}

// Labels left under 1.5 mm are said before printing: the warning small_labels counts those the
// sheets draw so (the CAD part at 100 mm with every face kept: its short edges; glue strips
// print their numbers at 1.5 mm at least), names the smallest and says what would help; a kit
// whose labels all print legibly has no such warning. (At 100 mm with detail auto the part
// printed 19 such labels until its small tunnels were plugged before its collapse, 2026-12-06.)
TEST(AssemblyAids, LabelsLeftSmallAreWarned) {
  JobOptions options;
  options.size_mm = 100;
  options.detail.mode = DetailMode::Full;
  const Printed printed = line_art("trimesh_ADIS16480_600.obj", options);
  ASSERT_TRUE(printed.doc.print);
  const auto small = small_labels(printed);
  ASSERT_GT(small.size(), 0u) << "the CAD part now prints every label legibly: find another";
  const NetRepair* warning = entry_of(printed.doc.warnings, "small_labels");
  ASSERT_NE(warning, nullptr);
  EXPECT_EQ(warning->count, small.size());
  double smallest = small.front().second;
  for (const auto& [text, size] : small) smallest = std::min(smallest, size);
  EXPECT_NE(warning->message.find(std::to_string(small.size()) + " of "), std::string::npos)
      << warning->message;
  std::smatch said;  // the SVG writes sizes rounded
  ASSERT_TRUE(
      std::regex_search(warning->message, said, std::regex(R"(the smallest ([0-9.e+-]+) mm)")))
      << warning->message;
  EXPECT_NEAR(std::stod(said[1].str()), smallest, 0.01) << warning->message;
  EXPECT_NE(warning->message.find("detail auto collapses them"), std::string::npos)
      << warning->message;
  // At 200 mm with detail auto the same part prints every label legibly.
  EXPECT_EQ(small_labels(cad_part()).size(), 0u);
  EXPECT_EQ(entry_of(cad_part().doc.warnings, "small_labels"), nullptr);
}

// Which labels give up the piece's name is decided on a first trial, before crowded labels move;
// the place away from its edge a label found then can be taken by the end. trimesh__groups at
// 400 faces with every face kept printed `141→P13` at 0.6 mm so: it had found a place across its
// edge in the first trial, and kept its name. The labels are placed in rounds since: a label
// still naming the piece and under 1.5 mm at the end of one is the plain number in the next
// (docs/print.md, "Build order"). Needs ../shared/data (the benchmark's meshes).
TEST(AssemblyAids, ANamedLabelLeftSmallIsThePlainNumberInTheNextRound) {
  const std::string file = shared_data_dir() + "/bench/400/trimesh__groups.obj";
  if (!std::filesystem::exists(file))
    GTEST_SKIP() << "needs ../shared/data: " << file << " is absent";
  const JobInput input = file_input(file);
  JobOptions options;
  options.layout = PageLayoutMode::Fit;
  options.colour = false;
  options.detail = {DetailMode::Full, 0};
  PipelineProgress quiet;
  const UnfoldOutcome out = run_pipeline(input, options, {}, {.svg_pages = true}, quiet);
  ASSERT_TRUE(out.print);
  const Printed printed{read_net_json(out.documents.net_json), out.documents.svg_pages, {}};
  std::size_t named = 0;
  for (const auto& [text, size] : sheet_labels(printed))
    named += text.find("→P") != std::string::npos;
  const auto small = small_labels(printed);
  for (const auto& [text, size] : small)
    ADD_FAILURE() << "label " << text << " at " << size << " mm";
  EXPECT_EQ(small.size(), 0u);
  EXPECT_EQ(out.print->small_labels, 0u);
  EXPECT_GT(named, 20u) << "the labels between pieces name the piece across";
  const NetCheckReport check = check_pieces(printed.doc.mesh, printed.doc.net, printed.doc.piece);
  EXPECT_TRUE(check.ok()) << check.summary();
}

/// A text of an SVG page as drawn: its corners (counter-clockwise on the page, y down), half an
/// em per character (the arrow one em) and 0.7 em high, about the centre it turns on.
struct DrawnText {
  std::string text;
  std::array<Vec2, 4> corners;
};

std::vector<DrawnText> drawn_texts(const std::string& svg, const std::string& group) {
  std::vector<DrawnText> out;
  const std::string g = svg_group(svg, group);
  static const std::regex text(
      "<text x=\"([-0-9.]+)\" y=\"([-0-9.]+)\" font-size=\"([0-9.]+)\"[^>]*"
      "rotate\\(([-0-9.]+) ([-0-9.]+) ([-0-9.]+)\\)\">([^<]+)</text>");
  for (auto it = std::sregex_iterator(g.begin(), g.end(), text); it != std::sregex_iterator();
       ++it) {
    const double size = std::stod((*it)[3]), angle = std::stod((*it)[4]) * std::numbers::pi / 180;
    const Vec2 centre{std::stod((*it)[5]), std::stod((*it)[6])};
    const std::string t = (*it)[7];
    double ems = 0;
    for (std::size_t k = 0; k < t.size(); ++k) {
      const auto byte = static_cast<unsigned char>(t[k]);
      if (byte < 0x80)
        ems += 0.5;
      else if (byte >= 0xC0)
        ems += 1;  // the first byte of a UTF-8 character (the arrow)
    }
    const Vec2 along{std::cos(angle), std::sin(angle)}, across{-along.y, along.x};
    const double w = 0.5 * ems * size, h = 0.35 * size;
    out.push_back({t,
                   {centre - w * along - h * across, centre + w * along - h * across,
                    centre + w * along + h * across, centre - w * along + h * across}});
  }
  return out;
}

/// True when two convex quadrilaterals overlap (no separating axis among their sides).
bool quads_overlap(const std::array<Vec2, 4>& a, const std::array<Vec2, 4>& b) {
  for (const auto* poly : {&a, &b})
    for (int k = 0; k < 4; ++k) {
      const Vec2 side = (*poly)[(k + 1) % 4] - (*poly)[k], normal{-side.y, side.x};
      double a_lo = INFINITY, a_hi = -INFINITY, b_lo = INFINITY, b_hi = -INFINITY;
      for (const Vec2 p : a)
        a_lo = std::min(a_lo, dot(normal, p)), a_hi = std::max(a_hi, dot(normal, p));
      for (const Vec2 p : b)
        b_lo = std::min(b_lo, dot(normal, p)), b_hi = std::max(b_hi, dot(normal, p));
      if (a_hi <= b_lo || b_hi <= a_lo) return false;
    }
  return true;
}

// Each piece's number prints clear of the edge labels, on the drawn sheets: where the centre of
// a face's inscribed circle is taken, points towards the face's corners and sides are tried
// (10 of the CAD part's 26 piece numbers lay over an edge label when only the centres were).
TEST(AssemblyAids, PieceNumbersPrintClearOfTheEdgeLabels) {
  for (const Printed* printed : {&duck(), &cad_part()}) {
    ASSERT_TRUE(printed->doc.print);
    std::size_t numbers = 0;
    for (int k = 0; k < static_cast<int>(printed->pages.size()); ++k) {
      if (k == printed->doc.print->overview_page) continue;
      std::vector<DrawnText> pieces, edges;
      for (DrawnText& t : drawn_texts(printed->pages[k], "labels"))
        (std::regex_match(t.text, std::regex("P[0-9]+")) ? pieces : edges).push_back(std::move(t));
      numbers += pieces.size();
      for (const DrawnText& p : pieces)
        for (const DrawnText& e : edges)
          EXPECT_FALSE(quads_overlap(p.corners, e.corners))
              << p.text << " over \"" << e.text << "\" on page " << k + 1;
    }
    EXPECT_EQ(numbers, printed->doc.pieces.size());
  }
}

/// The straight segments of an SVG group's open paths ("M x y L x y ..."), in page millimetres.
std::vector<std::array<Vec2, 2>> drawn_segments(const std::string& svg, const std::string& group) {
  std::vector<std::array<Vec2, 2>> out;
  const std::string g = svg_group(svg, group);
  static const std::regex path("<path d=\"([^\"]*)\"");
  static const std::regex step("([ML])([-0-9.]+) ([-0-9.]+)");
  for (auto it = std::sregex_iterator(g.begin(), g.end(), path); it != std::sregex_iterator();
       ++it) {
    const std::string d = (*it)[1];
    Vec2 last{};
    for (auto st = std::sregex_iterator(d.begin(), d.end(), step); st != std::sregex_iterator();
         ++st) {
      const Vec2 p{std::stod((*st)[2]), std::stod((*st)[3])};
      if ((*st)[1] == "L") out.push_back({last, p});
      last = p;
    }
  }
  return out;
}

/// True when `p` lies in the triangle or convex polygon `poly` (either orientation), up to
/// 1e-6 mm^2 of slack.
bool point_in_polygon(Vec2 p, const std::vector<Vec2>& poly) {
  bool neg = false, pos = false;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const double c = cross(poly[(k + 1) % poly.size()] - poly[k], p - poly[k]);
    neg = neg || c < -1e-6;
    pos = pos || c > 1e-6;
  }
  return !(neg && pos);
}

// Every edge label of 1.5 mm or more prints on the faces of the pieces (or its glue tab), where
// cutting out leaves it: the corners and the centre of each label's glyph box, as drawn, lie on
// a face or tab drawn on its page (on the
// CAD part 127 of its 432 labels, moved beside short edges, hung past their piece's outline
// before). A label that found no legible place at its edge prints farther away with a leader
// line, straight or of up to four lines end to end: each leader starts at a label of at least
// 1.5 mm and ends on a drawn cut line or tab hinge (its edge); the CAD part has leaders, and one
// that bends.
TEST(AssemblyAids, EveryLabelPrintsOnItsPieceAndLeadersEndOnTheirEdge) {
  std::size_t leaders = 0, bends = 0, longest = 0;
  for (const Printed* printed : {&duck(), &cad_part()}) {
    ASSERT_TRUE(printed->doc.print);
    for (int k = 0; k < static_cast<int>(printed->pages.size()); ++k) {
      if (k == printed->doc.print->overview_page) continue;
      const std::string& page = printed->pages[k];
      std::vector<std::vector<Vec2>> faces = svg_polygons(svg_group(page, "faces"));
      for (std::vector<Vec2>& tab : svg_polygons(svg_group(page, "tabs")))
        faces.push_back(std::move(tab));  // a label may print on its own glue tab
      // On a face or tab, or within 0.3 mm of one: the print samples nine points of a label's
      // box, so a corner may reach a hair past a notch in the outline between them.
      const auto on_a_face = [&](Vec2 p) {
        return std::any_of(faces.begin(), faces.end(), [&](const std::vector<Vec2>& f) {
          if (point_in_polygon(p, f)) return true;
          for (std::size_t j = 0; j < f.size(); ++j)
            if (segment_distance(p, f[j], f[(j + 1) % f.size()]) <= 0.3) return true;
          return false;
        });
      };
      std::vector<DrawnText> edge_labels;
      for (DrawnText& t : drawn_texts(page, "labels"))
        if (!std::regex_match(t.text, std::regex("P[0-9]+"))) edge_labels.push_back(std::move(t));
      for (const DrawnText& t : edge_labels) {
        const auto& c = t.corners;
        if (norm(c[3] - c[0]) < 0.7 * 1.5 - 1e-3) continue;  // under 1.5 mm: read by no one
        for (const Vec2 p : {c[0], c[1], c[2], c[3], 0.25 * (c[0] + c[1] + c[2] + c[3])})
          EXPECT_TRUE(on_a_face(p)) << "label \"" << t.text << "\" on page " << k + 1
                                    << " reaches past its piece at (" << p.x << ", " << p.y << ")";
      }
      // The edge: a cut line, or the hinge of its glue tab (drawn as a mountain fold).
      std::vector<std::array<Vec2, 2>> cuts = drawn_segments(page, "cut");
      for (const auto& hinge : drawn_segments(page, "mountain")) cuts.push_back(hinge);
      const std::vector<std::array<Vec2, 2>> drawn_leaders = drawn_segments(page, "leaders");
      // A leader with a bend is two lines, the second from where the first ends.
      const auto joins = [&](Vec2 p, int end) {
        return std::any_of(drawn_leaders.begin(), drawn_leaders.end(),
                           [&](const std::array<Vec2, 2>& l) { return norm(l[end] - p) < 1e-3; });
      };
      for (const std::array<Vec2, 2>& leader : drawn_leaders) {
        const Vec2 from = leader[0], to = leader[1];  // a lambda below takes `from`
        const bool first = !joins(from, 1), last = !joins(to, 0);
        leaders += first;
        bends += !first;
        if (first) {
          // At most four lines, end to end.
          std::size_t lines = 1;
          for (Vec2 end = to; joins(end, 0) && lines <= 4; ++lines)
            end =
                std::find_if(drawn_leaders.begin(), drawn_leaders.end(),
                             [&](const std::array<Vec2, 2>& l) { return norm(l[0] - end) < 1e-3; })
                    ->at(1);
          EXPECT_LE(lines, 4u) << "a leader of more than four lines on page " << k + 1;
          longest = std::max(longest, lines);
        }
        if (first) {
          // Starts at a label's box (the drawn glyph box is a little smaller than the label's).
          const auto starts =
              std::find_if(edge_labels.begin(), edge_labels.end(), [&](const DrawnText& t) {
                const auto& c = t.corners;
                double d = INFINITY;
                for (int j = 0; j < 4; ++j)
                  d = std::min(d, segment_distance(from, c[j], c[(j + 1) % 4]));
                return d < 0.3 * 1.5;
              });
          ASSERT_NE(starts, edge_labels.end()) << "a leader on page " << k + 1 << " starts at ("
                                               << from.x << ", " << from.y << "), at no label";
          const double height = norm(starts->corners[3] - starts->corners[0]) / 0.7;
          EXPECT_GE(height, 1.5 - 1e-3) << "leader to \"" << starts->text << "\"";
        }
        if (!last) continue;
        double to_cut = INFINITY;
        for (const auto& [a, b] : cuts) to_cut = std::min(to_cut, segment_distance(to, a, b));
        EXPECT_LT(to_cut, 1e-2) << "a leader on page " << k + 1 << " ends at (" << to.x << ", "
                                << to.y << "), on no edge";
      }
    }
  }
  EXPECT_GT(leaders, 0u) << "no label of the CAD part printed away from its edge";
  EXPECT_GT(bends, 0u) << "no leader of the CAD part bends";
  EXPECT_LE(longest, 4u);
}

// The overview is page 1: every piece on it once, captioned with the page the placements put it
// on; its build order names each piece's earlier neighbours; every page says "page k of n".
TEST(AssemblyAids, TheOverviewListsEveryPieceOnceWithItsSheet) {
  const Printed& printed = duck();
  const NetDocument& doc = printed.doc;
  ASSERT_TRUE(doc.print);
  ASSERT_EQ(doc.print->overview_page, 0);
  const int n = doc.print->pages;
  ASSERT_EQ(static_cast<std::size_t>(n), printed.pages.size());
  for (int k = 0; k < n; ++k) {
    const std::string mark =
        std::string("page ") + std::to_string(k + 1) + " of " + std::to_string(n);
    EXPECT_NE(printed.pages[k].find(mark), std::string::npos) << mark;
  }
  EXPECT_NE(printed.pages[0].find("overview"), std::string::npos);
  for (const PiecePlacement& p : doc.print->placements) EXPECT_GT(p.page, 0) << "P" << p.piece + 1;
  // The PDF has the same pages.
  std::size_t pdf_pages = 0;
  static const std::regex page_object("/Type\\s*/Page[^s]");
  for (auto it = std::sregex_iterator(printed.pdf.begin(), printed.pdf.end(), page_object);
       it != std::sregex_iterator(); ++it)
    ++pdf_pages;
  EXPECT_EQ(pdf_pages, static_cast<std::size_t>(n));

  // The sheet list: captions "page k: P1, P4", broken after a comma onto more lines when long.
  const std::vector<std::string> overview = overview_texts(printed.pages[0]);
  std::map<int, std::vector<int>> listed;  // piece -> pages it is listed on
  std::map<int, std::vector<int>> mapped;  // piece -> thumbnails its number is on (by count)
  static const std::regex caption("^page (\\d+):(.*)$"), names("P(\\d+)"),
      step("^P(\\d+) glues to (.*)$"), start("^P(\\d+): start (here|a new part)$"),
      alone("^P(\\d+)$");
  const Adjacency adj = adjacency(doc);
  std::set<int> steps;
  int caption_page = -1;
  bool more = false;  // the caption's last line ended in a comma: its next line goes on
  // The build order's step "P7 glues to P3, P4", broken after a comma onto more lines when long:
  // the step being read (-1: none) and the pieces named on its lines so far.
  int step_piece = -1;
  std::set<int> named;
  const auto read_step = [&](const std::string& line) {
    for (auto it = std::sregex_iterator(line.begin(), line.end(), names);
         it != std::sregex_iterator(); ++it)
      named.insert(std::stoi((*it)[1]) - 1);
    if (!line.empty() && line.back() == ',') return;  // goes on on the next line
    std::set<int> earlier;
    for (int q : adj.joins.at(step_piece))
      if (q < step_piece) earlier.insert(q);
    EXPECT_EQ(named, earlier) << "P" << step_piece + 1 << " glues to ... " << line;
    step_piece = -1;
  };
  for (const std::string& t : overview) {
    std::smatch m;
    if (step_piece >= 0) {
      read_step(t);
    } else if (more || std::regex_match(t, m, caption)) {
      if (!more) caption_page = std::stoi(m[1]) - 1;
      const std::string rest = more ? t : std::string(m[2]);
      for (auto it = std::sregex_iterator(rest.begin(), rest.end(), names);
           it != std::sregex_iterator(); ++it)
        listed[std::stoi((*it)[1]) - 1].push_back(caption_page);
      more = !rest.empty() && rest.back() == ',';
    } else if (std::regex_match(t, m, step)) {
      step_piece = std::stoi(m[1]) - 1;
      steps.insert(step_piece);
      named.clear();
      read_step(m[2]);
    } else if (std::regex_match(t, m, start)) {
      const int p = std::stoi(m[1]) - 1;
      steps.insert(p);
      for (int q : adj.joins.at(p)) EXPECT_GT(q, p) << t;
    } else if (std::regex_match(t, m, alone)) {
      mapped[std::stoi(m[1]) - 1].push_back(caption_page);
    }
  }
  ASSERT_EQ(listed.size(), doc.pieces.size());
  for (const auto& [p, pages] : listed) {
    ASSERT_EQ(pages.size(), 1u) << "P" << p + 1 << " listed more than once";
    EXPECT_EQ(pages[0], doc.print->placements.at(p).page) << "P" << p + 1;
  }
  EXPECT_EQ(steps.size(), doc.pieces.size()) << "one build step per piece";
  EXPECT_EQ(mapped.size(), doc.pieces.size()) << "each piece's number on its thumbnail";
  for (const auto& [p, on] : mapped) EXPECT_EQ(on.size(), 1u) << "P" << p + 1;
}

// The overview shows the model as built from two sides (the Duck is glTF: Y up, facing +Z; seen
// from the front, the right and above, then from the opposite side), each view an image beside
// the thumbnails with its pieces' numbers on it. Each number names the piece the model shows
// under it: a ray cast here from the number's centre into the mesh of the net JSON, fitted to
// the image as large as fits and centred, hits that piece first; or, for a number beside the
// model, at the far end of the line from it (within a quarter millimetre: the line ends on the
// middle of a pixel where the piece shows).
// Checks the views of `printed`'s overview, the model `up` and facing `front`; counts the numbers
// beside the model and the pieces numbered on a view.
void check_views(const Printed& printed, Vec3 up, Vec3 front, std::size_t& beside,
                 std::size_t& pieces_numbered) {
  const NetDocument& doc = printed.doc;
  const std::string& page = printed.pages[0];
  const std::vector<SvgBox> views = svg_images(page);
  ASSERT_EQ(views.size(), 2u) << "the overview shows the model from two sides";
  EXPECT_FALSE(views[0].overlaps(views[1]));
  const std::vector<SvgText> all = svg_texts(svg_group(page, "labels"));
  // The lines of the marks layer ("Mx yLx y").
  std::vector<std::array<Vec2, 2>> lines;
  {
    const std::string marks = svg_group(page, "marks");
    static const std::regex line("M([-0-9.]+) ([-0-9.]+)L([-0-9.]+) ([-0-9.]+)");
    for (auto it = std::sregex_iterator(marks.begin(), marks.end(), line);
         it != std::sregex_iterator(); ++it)
      lines.push_back({Vec2{std::stod((*it)[1]), std::stod((*it)[2])},
                       Vec2{std::stod((*it)[3]), std::stod((*it)[4])}});
  }
  std::size_t numbered = 0;
  beside = 0;
  std::set<int> shown;
  for (int v = 0; v < 2; ++v) {
    const SvgBox& box = views[v];
    EXPECT_GE(box.x0, 10 - 1e-6);  // A4 with 10 mm margins
    EXPECT_GE(box.y0, 10 - 1e-6);
    EXPECT_LE(box.x1, 200 + 1e-6);
    EXPECT_LE(box.y1, 287 + 1e-6);
    const Vec3 toward = (v == 0 ? 1.0 : -1.0) * (front + 0.8 * cross(up, front) + 0.6 * up);
    const Vec3 w = (1 / norm(toward)) * toward;
    Vec3 x = cross(up, w);
    x = (1 / norm(x)) * x;
    const Vec3 y = cross(w, x);
    double lo_x = 1e300, lo_y = 1e300, hi_x = -1e300, hi_y = -1e300;
    for (const Vec3& p : doc.mesh.vertices) {
      lo_x = std::min(lo_x, dot(p, x)), hi_x = std::max(hi_x, dot(p, x));
      lo_y = std::min(lo_y, dot(p, y)), hi_y = std::max(hi_y, dot(p, y));
    }
    const double s = std::min((box.x1 - box.x0) / (hi_x - lo_x), (box.y1 - box.y0) / (hi_y - lo_y));
    const Vec2 offset{0.5 * (box.x1 - box.x0 - s * (hi_x - lo_x)),
                      0.5 * (box.y1 - box.y0 - s * (hi_y - lo_y))};
    const auto on_page = [&](const Vec3& p) {
      return Vec2{box.x0 + offset.x + s * (dot(p, x) - lo_x),
                  box.y1 - offset.y - s * (dot(p, y) - lo_y)};
    };
    std::set<int> here;
    for (const SvgText& t : all) {
      const Vec2 c{t.x, t.y - 0.35 * t.size};
      if (!box.holds(c.x, c.y)) continue;
      std::smatch m;
      ASSERT_TRUE(std::regex_match(t.text, m, std::regex("P([0-9]+)"))) << t.text;
      const int piece = std::stoi(m[1]) - 1;
      ASSERT_LT(piece, static_cast<int>(doc.pieces.size())) << t.text;
      EXPECT_TRUE(here.insert(piece).second) << t.text << " twice on view " << v;
      EXPECT_GE(t.size, 2 - 1e-6) << t.text;
      // The face nearest the viewer under a point of the page (-1: none).
      const auto hit = [&](Vec2 at) {
        int out = -1;
        double nearest = -1e300;
        for (std::size_t f = 0; f < doc.mesh.faces.size(); ++f) {
          const auto& tri = doc.mesh.faces[f];
          const Vec2 a = on_page(doc.mesh.vertices[tri[0]]), b = on_page(doc.mesh.vertices[tri[1]]),
                     d = on_page(doc.mesh.vertices[tri[2]]);
          const double area = cross(b - a, d - a);
          if (std::abs(area) < 1e-12) continue;
          const double l1 = cross(at - a, d - a) / area, l2 = cross(b - a, at - a) / area;
          if (l1 < 0 || l2 < 0 || l1 + l2 > 1) continue;
          const double depth = (1 - l1 - l2) * dot(doc.mesh.vertices[tri[0]], w) +
                               l1 * dot(doc.mesh.vertices[tri[1]], w) +
                               l2 * dot(doc.mesh.vertices[tri[2]], w);
          if (depth > nearest) nearest = depth, out = static_cast<int>(f);
        }
        return out;
      };
      const int under = hit(c);
      ++numbered;
      if (under >= 0) {
        EXPECT_EQ(doc.piece[under], piece)
            << t.text << " on view " << v << " lies on P" << doc.piece[under] + 1;
        continue;
      }
      // Beside the model: the line that starts on its box, and where it ends.
      const double reach = 0.5 * 0.6 * t.size * static_cast<double>(t.text.size()) + 0.5;
      const std::array<Vec2, 2>* line = nullptr;
      for (const auto& l : lines)
        if (std::abs(l[0].x - c.x) <= reach && std::abs(l[0].y - c.y) <= 0.5 * t.size + 0.5)
          line = &l;
      ASSERT_NE(line, nullptr) << t.text << " on view " << v << " lies off the model, no line";
      const Vec2 end = (*line)[1];
      bool found = false;
      for (const Vec2 d :
           {Vec2{0, 0}, Vec2{0.25, 0}, Vec2{-0.25, 0}, Vec2{0, 0.25}, Vec2{0, -0.25}}) {
        const int f = hit(end + d);
        found |= f >= 0 && doc.piece[f] == piece;
      }
      EXPECT_TRUE(found) << t.text << " on view " << v << ": its line ends off its piece";
      ++beside;
    }
    shown.insert(here.begin(), here.end());
  }
  EXPECT_GE(numbered, 10u);
  pieces_numbered = shown.size();
}

TEST(AssemblyAids, TheOverviewShowsTheModelFromTwoSidesWithEachPieceNumberedWhereItShows) {
  std::size_t beside = 0, numbered = 0;
  check_views(duck(), {0, 1, 0}, {0, 0, 1}, beside, numbered);  // glTF: Y up, facing +Z
  if (HasFatalFailure()) return;
  EXPECT_GE(beside, 1u) << "a piece that shows too little for its number on it";
  EXPECT_GE(4 * numbered, 3 * duck().doc.pieces.size()) << "most pieces numbered on a view";
}

// An STL model stands on the printer's bed: Z up, facing -Y.
TEST(AssemblyAids, TheViewsOfAnStlModelStandZUp) {
  const Printed printed = line_art("thingi10k_65004.stl");
  ASSERT_TRUE(printed.doc.print);
  ASSERT_EQ(printed.doc.print->overview_page, 0);
  std::size_t beside = 0, numbered = 0;
  check_views(printed, {0, 0, 1}, {0, -1, 0}, beside, numbered);
  if (HasFatalFailure()) return;
  EXPECT_GE(2 * numbered, printed.doc.pieces.size()) << "half the pieces numbered on a view";
}

// No text on the overview covers another: the pieces' numbers on the thumbnails, where small
// pieces lie close, included (on this part's 47 pieces four numbers covered others when each sat
// at its piece's label), and no piece's number crosses a cut line. Boxes of half an em per
// character and 0.7 em high (digits and capitals), from the drawn SVG.
TEST(AssemblyAids, NoTextOnTheOverviewCoversAnother) {
  JobOptions options;
  options.layout = PageLayoutMode::Fit;
  options.detail = {DetailMode::Full, 0};  // every face: auto collapses its short edges
  // Time for every way of the fit search: under ASan the default minute's half ran out after
  // fewer ways, and another layout, of 20 pieces, was printed.
  options.time_limit = 600;
  options.merge_budget = light_merge(options.merge_budget);  // more pieces, if anything
  PipelineProgress quiet;
  const UnfoldOutcome out =
      run_pipeline(data_file("trimesh_ADIS16480_600.obj"), options, {}, {.svg_pages = true}, quiet);
  const Printed printed{read_net_json(out.documents.net_json), out.documents.svg_pages, {}};
  ASSERT_TRUE(printed.doc.print);
  ASSERT_EQ(printed.doc.print->overview_page, 0);
  struct Box {
    double x0, y0, x1, y1;
    std::string text;
  };
  std::vector<Box> boxes;
  std::size_t numbers = 0;
  for (const SvgText& t : svg_texts(svg_group(printed.pages[0], "labels"))) {
    const double y = t.y - 0.35 * t.size;  // the text's visual centre
    numbers += std::regex_match(t.text, std::regex("P[0-9]+"));
    const double half_w = 0.25 * t.size * static_cast<double>(t.text.size());
    const double x0 = t.start ? t.x : t.x - half_w;  // the build order's lines start at x
    boxes.push_back({x0, y - 0.35 * t.size, x0 + 2 * half_w, y + 0.35 * t.size, t.text});
  }
  std::size_t on_thumbnails = 0;
  for (const std::string& t : overview_texts(printed.pages[0]))
    on_thumbnails += std::regex_match(t, std::regex("P[0-9]+"));
  EXPECT_GE(on_thumbnails, printed.doc.pieces.size()) << "each piece's number on its thumbnail";
  EXPECT_GT(numbers, on_thumbnails) << "and numbers on the views of the model";
  EXPECT_GT(printed.doc.pieces.size(), 20u) << "the part no longer has many small pieces";
  for (std::size_t a = 0; a < boxes.size(); ++a)
    for (std::size_t b = a + 1; b < boxes.size(); ++b) {
      const Box &p = boxes[a], &q = boxes[b];
      EXPECT_FALSE(p.x0 < q.x1 && q.x0 < p.x1 && p.y0 < q.y1 && q.y0 < p.y1)
          << "\"" << p.text << "\" covers \"" << q.text << "\"";
    }
  // No piece's number crosses a cut line of the thumbnails (a small piece's number goes beside
  // it, with a line back to it): each segment of the cut layer's paths ("Mx yLx yLx y..."),
  // clipped to each number's box.
  const std::string cut = svg_group(printed.pages[0], "cut");
  static const std::regex subpath("M([-0-9. L]+)"), point("([-0-9.]+) ([-0-9.]+)");
  std::size_t lines = 0;
  for (auto it = std::sregex_iterator(cut.begin(), cut.end(), subpath);
       it != std::sregex_iterator(); ++it) {
    const std::string run = (*it)[1];
    std::vector<Vec2> points;
    for (auto p = std::sregex_iterator(run.begin(), run.end(), point); p != std::sregex_iterator();
         ++p)
      points.push_back({std::stod((*p)[1]), std::stod((*p)[2])});
    for (std::size_t k = 0; k + 1 < points.size(); ++k) {
      ++lines;
      const Vec2 a = points[k], b = points[k + 1];
      for (const Box& box : boxes) {
        if (!std::regex_match(box.text, std::regex("P[0-9]+"))) continue;
        // Liang-Barsky: the part of a + t (b - a), t in [0, 1], inside the box.
        double t0 = 0, t1 = 1;
        const Vec2 d = b - a;
        for (const auto& [p, q] : {std::pair{-d.x, a.x - box.x0}, std::pair{d.x, box.x1 - a.x},
                                   std::pair{-d.y, a.y - box.y0}, std::pair{d.y, box.y1 - a.y}}) {
          if (p == 0) {
            if (q < 0) t0 = 2;  // parallel to this side and outside it
            continue;
          }
          const double t = q / p;
          if (p < 0)
            t0 = std::max(t0, t);
          else
            t1 = std::min(t1, t);
        }
        EXPECT_FALSE(t0 < t1) << "\"" << box.text << "\" crosses the cut line (" << a.x << ", "
                              << a.y << ") - (" << b.x << ", " << b.y << ")";
      }
    }
  }
  EXPECT_GT(lines, 100u) << "the thumbnails' cut lines";
}

// overview no: the sheets alone, from page 1, in build order too; the net JSON has no
// overview_page.
TEST(AssemblyAids, WithoutTheOverviewTheSheetsStartAtPageOne) {
  JobOptions options;
  options.layout = PageLayoutMode::Fit;
  options.overview = false;
  options.colour = false;
  lighten(options);  // as duck()'s
  PipelineProgress quiet;
  const UnfoldOutcome out =
      run_pipeline(data_file("Duck.glb"), options, {}, {.svg_pages = true}, quiet);
  const NetDocument doc = read_net_json(out.documents.net_json);
  ASSERT_TRUE(doc.print);
  EXPECT_EQ(doc.print->overview_page, -1);
  EXPECT_EQ(out.documents.net_json.find("overview_page"), std::string::npos);
  const NetCheckReport check = check_pieces(doc.mesh, doc.net, doc.piece);
  EXPECT_TRUE(check.ok()) << check.summary();
  const Printed& with = duck();
  EXPECT_EQ(doc.print->pages + 1, with.doc.print->pages);
  ASSERT_EQ(static_cast<std::size_t>(doc.print->pages), out.documents.svg_pages.size());
  for (const std::string& svg : out.documents.svg_pages)
    EXPECT_EQ(svg.find("overview"), std::string::npos);
  // The same pieces in the same order, each one page earlier.
  ASSERT_EQ(doc.pieces.size(), with.doc.pieces.size());
  EXPECT_EQ(doc.piece, with.doc.piece);
  for (std::size_t p = 0; p < doc.pieces.size(); ++p)
    EXPECT_EQ(doc.print->placements[p].page + 1, with.doc.print->placements[p].page);
  // Sheets in build order: the lowest piece on each page grows with the page.
  std::vector<int> lowest(static_cast<std::size_t>(doc.print->pages), 1 << 30);
  for (const PiecePlacement& p : doc.print->placements)
    lowest[p.page] = std::min(lowest[p.page], p.piece);
  EXPECT_TRUE(std::is_sorted(lowest.begin(), lowest.end()));
}

// Paper too small for a legible overview (sample.obj at 20 mm on 30 x 30 mm paper, 5 mm
// margins): the kit prints without it, asked for or not, and the result says so; it once
// planned overview pages without end and ran out of memory.
TEST(AssemblyAids, PaperTooSmallForTheOverviewPrintsTheKitWithoutIt) {
  for (const std::optional<bool> asked : {std::optional<bool>{}, std::optional<bool>{true}}) {
    SCOPED_TRACE(asked ? "overview yes" : "overview unset");
    JobOptions options;
    options.paper = "30x30mm";
    options.margin_mm = 5;
    options.overlap_mm = 1;
    options.size_mm = 20;
    options.overview = asked;
    options.colour = false;
    PipelineProgress quiet;
    const UnfoldOutcome out =
        run_pipeline(data_file("sample.obj"), options, {}, {.svg_pages = true}, quiet);
    const NetDocument doc = read_net_json(out.documents.net_json);
    ASSERT_TRUE(doc.print);
    EXPECT_GT(doc.pieces.size(), 1u);
    EXPECT_EQ(doc.print->overview_page, -1);
    const NetRepair* warning = entry_of(doc.warnings, "overview_left_out");
    ASSERT_NE(warning, nullptr);
    EXPECT_NE(warning->message.find("30x30mm"), std::string::npos) << warning->message;
    ASSERT_EQ(static_cast<std::size_t>(doc.print->pages), out.documents.svg_pages.size());
    for (const std::string& svg : out.documents.svg_pages)
      EXPECT_EQ(svg.find("overview"), std::string::npos);
    std::set<int> pages;
    for (const PiecePlacement& p : doc.print->placements) pages.insert(p.page);
    EXPECT_EQ(pages.count(0), 1u) << "the sheets start at page 1";
    const NetCheckReport check = check_pieces(doc.mesh, doc.net, doc.piece);
    EXPECT_TRUE(check.ok()) << check.summary();
  }
}

}  // namespace
}  // namespace papernet::test
