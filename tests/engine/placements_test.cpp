// The net JSON's `print` (DESIGN.md §4): each piece's placement, checked against the pages as
// drawn in their SVGs, not against the layout's own data; and the net as printed passes the net
// checker, one root per piece.
#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "api/net_json.h"
#include "core/io/load.h"
#include "core/unfold/net_check.h"
#include "engine/pipeline.h"
#include "tests/support/job_input.h"
#include "tests/support/sanitized.h"
#include "tests/support/svg.h"

namespace papernet::test {
namespace {

// A4 with 10 mm margins (the defaults).
constexpr double kWidth = 210, kHeight = 297, kMargin = 10;
// The transforms against the drawing: SVG numbers are rounded to 1 µm.
constexpr double kTolerance = 0.05;

/// The closed polygons of one SVG group.
std::vector<std::vector<Vec2>> polygons(const std::string& svg, const std::string& id) {
  return svg_polygons(svg_group(svg, id));
}

Vec2 apply(const std::array<double, 6>& t, Vec2 p) {
  return {t[0] * p.x + t[2] * p.y + t[4], t[1] * p.x + t[3] * p.y + t[5]};
}

/// The face's net points mapped by its piece's transform.
std::array<Vec2, 3> mapped(const NetDocument& doc, std::size_t face) {
  const auto& t = doc.print->placements.at(doc.piece[face]).transform;
  std::array<Vec2, 3> out;
  for (int k = 0; k < 3; ++k) out[k] = apply(t, doc.net.points[face][k]);
  return out;
}

/// The drawn face polygon whose corners are the three points within kTolerance, or -1.
int drawn_match(const std::array<Vec2, 3>& face, const std::vector<std::vector<Vec2>>& drawn) {
  for (int i = 0; i < static_cast<int>(drawn.size()); ++i) {
    if (drawn[i].size() != 3) continue;
    bool all = true;
    for (Vec2 p : face) {
      bool near = false;
      for (Vec2 q : drawn[i]) near = near || norm(p - q) <= kTolerance;
      all = all && near;
    }
    if (all) return i;
  }
  return -1;
}

struct Printed {
  NetDocument doc;
  std::vector<std::string> pages;  ///< each page's SVG
};

Printed print(const std::string& file, JobOptions options) {
  options.strategy = Strategy::TU;
  lighten(options);
  PipelineProgress quiet;
  const UnfoldOutcome out =
      run_pipeline(data_file(file), options, {}, {.svg_pages = true, .pdf = true}, quiet);
  return {read_net_json(out.documents.net_json), out.documents.svg_pages};
}

/// The net as printed is a valid net of each piece: one tree (one root) per piece, and the
/// `pieces` array counts each piece's faces and names a part of the input.
void expect_pieces_check(const NetDocument& doc) {
  const NetCheckReport check = check_pieces(doc.mesh, doc.net, doc.piece);
  EXPECT_TRUE(check.ok()) << check.summary();
  std::vector<int> roots(doc.pieces.size()), faces(doc.pieces.size());
  for (std::size_t f = 0; f < doc.piece.size(); ++f) {
    ++faces[doc.piece[f]];
    roots[doc.piece[f]] += doc.net.parent[f] < 0;
  }
  for (std::size_t p = 0; p < doc.pieces.size(); ++p) {
    EXPECT_EQ(roots[p], 1) << "piece " << p;
    EXPECT_EQ(static_cast<std::size_t>(faces[p]), doc.pieces[p].faces) << "piece " << p;
    EXPECT_LT(doc.pieces[p].component, doc.input.components) << "piece " << p;
  }
}

/// `file` printed with layout fit at the defaults (200 mm on A4), once per process.
const Printed& printed_fit(const std::string& file) {
  static std::map<std::string, Printed> done;
  auto it = done.find(file);
  if (it == done.end()) {
    JobOptions options;
    options.layout = PageLayoutMode::Fit;
    it = done.emplace(file, print(file, options)).first;
  }
  return it->second;
}

class FitPlacements : public ::testing::TestWithParam<const char*> {};

// Several sheets each: sample.obj 4, the sensor 13, the others 4 (A4 at 200 mm).
INSTANTIATE_TEST_SUITE_P(Meshes, FitPlacements,
                         ::testing::Values("sample.obj", "trimesh_ADIS16480_600.obj",
                                           "testplate.glb", "mirror.ply"),
                         [](const auto& info) {
                           std::string name = info.param;
                           return name.substr(0, name.find('.'));
                         });

// Every face's net points, mapped by its piece's transform, land on a face polygon drawn on its
// piece's page, each drawn face matched once; every mapped face lies inside the printable area.
TEST_P(FitPlacements, TransformsLandEveryFaceOnItsDrawnPageInsideThePrintableArea) {
  const Printed& printed = printed_fit(GetParam());
  const NetDocument& doc = printed.doc;
  ASSERT_TRUE(doc.print);
  EXPECT_EQ(doc.print->layout, "fit");
  EXPECT_EQ(doc.print->paper, "A4");
  EXPECT_EQ(doc.print->page_width_mm, kWidth);
  EXPECT_EQ(doc.print->page_height_mm, kHeight);
  EXPECT_GT(doc.print->mm_per_unit, 0);
  ASSERT_EQ(static_cast<std::size_t>(doc.print->pages), printed.pages.size());
  EXPECT_GT(printed.pages.size(), 1u);
  ASSERT_EQ(doc.print->placements.size(), doc.pieces.size());
  EXPECT_TRUE(doc.print->tiles.empty());

  std::vector<std::vector<std::vector<Vec2>>> drawn;
  for (const std::string& svg : printed.pages) drawn.push_back(polygons(svg, "faces"));
  std::vector<std::vector<char>> used(drawn.size());
  for (std::size_t k = 0; k < drawn.size(); ++k) used[k].assign(drawn[k].size(), 0);
  std::size_t missed = 0, outside = 0;
  for (std::size_t f = 0; f < doc.mesh.faces.size(); ++f) {
    const PiecePlacement& placed = doc.print->placements[doc.piece[f]];
    EXPECT_EQ(placed.piece, doc.piece[f]);
    ASSERT_GE(placed.page, 0);
    ASSERT_LT(placed.page, doc.print->pages);
    const std::array<Vec2, 3> face = mapped(doc, f);
    for (Vec2 p : face)
      outside += p.x < kMargin - 1e-6 || p.y < kMargin - 1e-6 || p.x > kWidth - kMargin + 1e-6 ||
                 p.y > kHeight - kMargin + 1e-6;
    const int match = drawn_match(face, drawn[placed.page]);
    if (match < 0 || used[placed.page][match]) {
      ++missed;
      continue;
    }
    used[placed.page][match] = 1;
  }
  EXPECT_EQ(missed, 0u) << "faces whose mapped points are on no drawn face of their page";
  EXPECT_EQ(outside, 0u) << "mapped corners outside the printable area";
  std::size_t drawn_faces = 0;
  for (const auto& page : drawn) drawn_faces += page.size();
  EXPECT_EQ(drawn_faces, doc.mesh.faces.size());
}

// The pieces as printed: cut to fit a sheet, each a tree of its own that the net checker
// passes, each naming the part it was cut from and inheriting its result.
TEST_P(FitPlacements, TheNetAsPrintedPassesTheNetCheckerOneRootPerPiece) {
  const Printed& printed = printed_fit(GetParam());
  const NetDocument& doc = printed.doc;
  ASSERT_TRUE(doc.print);
  EXPECT_GT(doc.pieces.size(), doc.input.components) << "nothing was cut to fit";
  expect_pieces_check(doc);
  // Pieces are numbered in build order (docs/print.md): a part's pieces one after another,
  // every part printed.
  std::set<std::size_t> parts_done;
  for (std::size_t p = 0; p < doc.pieces.size(); ++p) {
    const std::size_t c = doc.pieces[p].component;
    if (p > 0 && c != doc.pieces[p - 1].component) {
      EXPECT_TRUE(parts_done.insert(doc.pieces[p - 1].component).second) << "piece " << p;
    }
    EXPECT_FALSE(parts_done.count(c)) << "piece " << p << ": its part came before";
  }
  parts_done.insert(doc.pieces.back().component);
  EXPECT_EQ(parts_done.size(), doc.input.components);
  // Each piece inherits its part's result and distance: the same for all pieces of a part.
  std::map<std::size_t, const NetPiece*> first_of_part;
  for (const NetPiece& p : doc.pieces) {
    const NetPiece& first = *first_of_part.emplace(p.component, &p).first->second;
    EXPECT_EQ(p.result, first.result);
    EXPECT_EQ(p.hausdorff, first.hausdorff);
  }
}

// Without a print, the pieces stay the parts of the input, and there is no `print`.
TEST(Placements, WithoutAPrintThePiecesAreTheParts) {
  PipelineProgress quiet;
  JobOptions options;
  options.strategy = Strategy::TU;
  options.size_mm = 400;
  lighten(options);
  const UnfoldOutcome out = run_pipeline(data_file("sample.obj"), options, {}, {}, quiet);
  const NetDocument doc = read_net_json(out.documents.net_json);
  EXPECT_FALSE(doc.print);
  ASSERT_EQ(doc.pieces.size(), 1u);
  EXPECT_EQ(doc.pieces[0].faces, doc.mesh.faces.size());
  EXPECT_FALSE(nlohmann::json::parse(out.documents.net_json).contains("print"));
  // Paper none: one drawing of the whole net, no sheets to place pieces on.
  options.paper = "none";
  const UnfoldOutcome unpaged =
      run_pipeline(data_file("sample.obj"), options, {}, {.svg_pages = true}, quiet);
  EXPECT_FALSE(read_net_json(unpaged.documents.net_json).print);
}

// A part with no overlap-free net in one piece (plain Tabu Unfolding, which took 1.6 s here to
// remove the steepest-edge start's overlaps on this CAD part of 1,466 faces, given a millisecond)
// is unfolded in pieces grown from single faces (14), with a warning: every face folds into its
// own place, each piece is one tree the net checker passes, and the print lands every face on
// its page.
TEST(Placements, APartWithNoNetInOnePieceIsUnfoldedInGrownPieces) {
  JobOptions options;
  options.detail = {DetailMode::Full, 0};
  options.time_limit = 1e-3;
  const Printed printed = print("thingi10k_65004.stl", options);
  const NetDocument& doc = printed.doc;
  const NetRepair* warning = entry_of(doc.warnings, "unfolded_in_pieces");
  ASSERT_NE(warning, nullptr);
  EXPECT_EQ(warning->count, 1u);
  EXPECT_EQ(doc.result, "complete");
  EXPECT_EQ(doc.mesh.faces.size(), 1466u);
  EXPECT_EQ(doc.input.components, 1u);
  ASSERT_TRUE(doc.print);
  EXPECT_GT(doc.pieces.size(), 1u);
  expect_pieces_check(doc);
  ASSERT_EQ(static_cast<std::size_t>(doc.print->pages), printed.pages.size());
  std::vector<std::vector<std::vector<Vec2>>> drawn;
  std::size_t drawn_faces = 0, missed = 0;
  for (const std::string& svg : printed.pages) {
    drawn.push_back(polygons(svg, "faces"));
    drawn_faces += drawn.back().size();
  }
  for (std::size_t f = 0; f < doc.mesh.faces.size(); ++f) {
    const int page = doc.print->placements.at(doc.piece[f]).page;
    ASSERT_GE(page, 0);
    ASSERT_LT(page, doc.print->pages);
    missed += drawn_match(mapped(doc, f), drawn[page]) < 0;
  }
  EXPECT_EQ(missed, 0u) << "faces whose mapped points are on no drawn face of their page";
  EXPECT_EQ(drawn_faces, doc.mesh.faces.size());
}

// Tiled, a piece spans pages: page -1, the transform maps into the tile grid's frame, and each
// page shows its listed window of it at the page's margin.
TEST(Placements, TiledPiecesMapIntoTheTileGridEachPageShowingItsWindow) {
  JobOptions options;
  options.layout = PageLayoutMode::Tile;
  options.size_mm = 400;
  const Printed printed = print("sample.obj", options);
  const NetDocument& doc = printed.doc;
  ASSERT_TRUE(doc.print);
  EXPECT_EQ(doc.print->layout, "tile");
  ASSERT_GT(printed.pages.size(), 1u);
  ASSERT_EQ(doc.print->tiles.size(), printed.pages.size());
  ASSERT_EQ(doc.pieces.size(), 1u);
  EXPECT_EQ(doc.print->placements.at(0).page, -1);
  expect_pieces_check(doc);
  const double margin = doc.print->margin_mm;
  EXPECT_EQ(margin, kMargin);
  std::vector<std::vector<std::vector<Vec2>>> drawn;
  for (const std::string& svg : printed.pages) drawn.push_back(polygons(svg, "faces"));
  std::size_t shown = 0, missed = 0;
  std::set<std::size_t> faces_shown;
  for (std::size_t f = 0; f < doc.mesh.faces.size(); ++f) {
    const std::array<Vec2, 3> face = mapped(doc, f);
    const Vec2 centre = (1.0 / 3) * (face[0] + face[1] + face[2]);
    for (const PageWindow& tile : doc.print->tiles) {
      const auto [x, y, w, h] = tile.window_mm;
      if (centre.x < x || centre.x > x + w || centre.y < y || centre.y > y + h) continue;
      std::array<Vec2, 3> on_page;
      for (int k = 0; k < 3; ++k) on_page[k] = face[k] + Vec2{margin - x, margin - y};
      ++shown;
      faces_shown.insert(f);
      missed += drawn_match(on_page, drawn.at(tile.page)) < 0;
    }
  }
  EXPECT_EQ(missed, 0u) << "of " << shown << " faces shown on tiles";
  EXPECT_EQ(faces_shown.size(), doc.mesh.faces.size()) << "every face's centre is on some tile";
}

}  // namespace
}  // namespace papernet::test
