// The job's time limit bounds the whole run (issue 23): load, unfold, the tab-room pass and the
// print end within the limit plus a second, with the best result the time allowed. The only
// timed tests of the suite, in their own executable: ctest runs them alone (RUN_SERIAL, label
// "timed"), and the sanitizer runs leave them out (SANITIZE_SKIP in the Makefile), where they would
// measure the sanitizer's slowness.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <string>

#include "core/io/load.h"
#include "core/unfold/net_check.h"
#include "engine/pipeline.h"
#include "tests/support/job_input.h"
#include "tests/support/paths.h"

namespace papernet::test {
namespace {

// Runs the pipeline and checks that it ends within its time limit plus a second, with a net
// that passes the checker; `seconds`: how long it took.
UnfoldOutcome run_within_limit(const JobInput& input, const JobOptions& options,
                               const DocumentRequest& documents, double& seconds) {
  PipelineProgress quiet;
  const auto start = std::chrono::steady_clock::now();
  UnfoldOutcome out = run_pipeline(input, options, {}, documents, quiet);
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double limit = options.time_limit.value();
  EXPECT_LE(seconds, limit + 1) << "the job took " << seconds << " s with a limit of " << limit
                                << " s";
  const NetCheckReport check = check_pieces(out.net.mesh, out.net.net, out.net.piece);
  EXPECT_TRUE(check.ok()) << check.summary();
  return out;
}

// Runs `file` (in ../shared/data) with a 10 s limit, every face kept and every document, and
// checks that it ends within 11 s with a checked net and its documents.
void expect_within_limit(const std::string& name, MeshFormat format) {
  const std::string file = papernet::test::shared_data_dir() + "/meshes/" + name;
  if (!std::filesystem::exists(file))
    GTEST_SKIP() << "needs ../shared/data: " << file << " is absent";
  JobInput input;
  input.mesh = read_mesh_file(file, 64 << 20);
  input.format = format;
  JobOptions options;  // AUTO, tabs auto, A4 at 200 mm
  options.time_limit = 10;
  options.detail = {DetailMode::Full, 0};  // every face: detail auto would collapse it first
  double seconds = 0;
  const UnfoldOutcome out =
      run_within_limit(input, options, {.svg = true, .pdf = true, .glb = true}, seconds);
  // Its best result: a checked net (of a coarser mesh when the uncollapse was cut short), with
  // every document.
  EXPECT_TRUE(out.net.result == "complete" || out.net.result == "approximate") << out.net.result;
  ASSERT_TRUE(out.print);
  EXPECT_GT(out.print->pages, 0);
  EXPECT_EQ(out.documents.pdf.substr(0, 5), "%PDF-");
  EXPECT_FALSE(out.documents.svg.empty());
  EXPECT_EQ(out.documents.glb.substr(0, 4), "glTF");
  std::cout << "[ figures  ] " << seconds << " s, " << out.net.result << ", "
            << out.net.mesh.faces.size() << " of " << out.net.input.faces << " faces, "
            << out.print->pages << " pages\n";
}

TEST(TimeLimit, ALargeMeshEndsWithinItsLimitWithItsBestResult) {
  // A 76,840-face scan: more than 10 s would take it to the full mesh, and tabs and print.
  expect_within_limit("thingi-like/thingi10k__73416.stl", MeshFormat::Stl);
}

TEST(TimeLimit, ALargeNetIsPrintedWithinTheLimit) {
  // A 20,088-face CAD part whose uncollapse reaches 15,000-20,000 faces in 10 s: the print of so
  // large a net takes seconds (3 s for 18,000 faces), which the unfold leaves it. It ended after
  // 13 s when the print had a fixed tenth of the limit.
  expect_within_limit("classic/c3d__rocker-arm.obj", MeshFormat::Obj);
}

TEST(TimeLimit, AColourNetTiledOverManyPagesIsPrintedWithinTheLimit) {
  // The Duck on 50 x 50 mm paper: a face is larger than its printable area, so the net is tiled,
  // over 560 pages, each drawn in colour. Each page painted the whole net's colour, clipped to
  // the page: 169 s with a limit of 10 s (its pages at the lowest resolution), 6 s now
  // (docs/colour.md, "Time limit").
  const JobInput input = data_file("Duck.glb");
  JobOptions options;  // detail auto, colour auto, 200 mm
  options.time_limit = 10;
  options.paper = "50x50mm";
  double seconds = 0;
  const UnfoldOutcome out =
      run_within_limit(input, options, {.svg_pages = true, .pdf = true, .glb = true}, seconds);
  ASSERT_TRUE(out.print);
  EXPECT_EQ(out.print->layout, "tile");
  EXPECT_GT(out.print->pages, 100);
  ASSERT_EQ(out.documents.svg_pages.size(), static_cast<std::size_t>(out.print->pages));
  std::size_t coloured = 0;  // pages with the Duck's colour on them
  for (const std::string& page : out.documents.svg_pages)
    coloured += page.find("<image") != std::string::npos;
  EXPECT_GT(coloured, 0u);
  EXPECT_EQ(out.documents.pdf.substr(0, 5), "%PDF-");
  std::cout << "[ figures  ] " << seconds << " s, " << out.print->pages << " pages, " << coloured
            << " with colour\n";
}

TEST(TimeLimit, LargeColourPagesAreDrawnWithinTheLimit) {
  // The Duck at 800 mm on A0 paper: five sheets, each 134 million pixels of colour at 300 dpi,
  // about 4 s to draw and write. Given 8 s, it ended after 14 s: the first sheet was drawn at
  // 300 dpi before any page had been timed. Now the pages' resolution is chosen from the first
  // sheet on, from the machine's pace until the pages' own is measured (docs/colour.md, "Time
  // limit").
  const JobInput input = data_file("Duck.glb");
  JobOptions options;  // detail auto, colour auto, 300 dpi
  options.time_limit = 8;
  options.paper = "841x1189mm";
  options.size_mm = 800;
  double seconds = 0;
  const UnfoldOutcome out = run_within_limit(input, options, {.pdf = true}, seconds);
  ASSERT_TRUE(out.print);
  ASSERT_TRUE(out.net.print);
  ASSERT_EQ(out.net.print->overview_page, 0);
  ASSERT_GE(out.print->pages, 3);
  const NetRepair* warning = entry_of(out.net.warnings, "colour_resolution_lowered");
  ASSERT_NE(warning, nullptr);
  EXPECT_NE(warning->message.find("pages 2 to "), std::string::npos) << warning->message;
  EXPECT_EQ(out.documents.pdf.substr(0, 5), "%PDF-");
  std::cout << "[ figures  ] " << seconds << " s, " << out.print->pages
            << " pages: " << warning->message << "\n";
}

TEST(TimeLimit, PagesPrintWithoutColourWhereEvenTheLowestResolutionWouldOverrun) {
  // The milk truck at 2,430 faces tiled on 50 x 50 mm paper: 777 pages, each painting its faces'
  // many small triangles, a cost the resolution hardly lowers (42 s with a limit of 10 s, every
  // page at 50 dpi but the first). Now the pages past the time print in line art, with a warning
  // naming them; those before keep their colour.
  const JobInput input = data_file("CesiumMilkTruck/CesiumMilkTruck.gltf");
  JobOptions options;
  options.time_limit = 10;
  options.paper = "50x50mm";
  options.detail = {DetailMode::Faces, 3000};
  double seconds = 0;
  const UnfoldOutcome out =
      run_within_limit(input, options, {.svg_pages = true, .pdf = true}, seconds);
  ASSERT_TRUE(out.print);
  EXPECT_EQ(out.print->layout, "tile");
  const auto& pages = out.documents.svg_pages;
  ASSERT_EQ(pages.size(), static_cast<std::size_t>(out.print->pages));
  const NetRepair* warning = entry_of(out.net.warnings, "colour_left_out");
  ASSERT_NE(warning, nullptr);
  const std::size_t without = warning->count, first = pages.size() - without;
  EXPECT_NE(warning->message.find("pages " + std::to_string(first + 1) + " to " +
                                  std::to_string(pages.size()) + " print without their colour"),
            std::string::npos)
      << warning->message;
  // Colour on the first page, and on none from the first named on.
  ASSERT_GT(first, 0u);
  EXPECT_NE(pages[0].find("<image"), std::string::npos);
  for (std::size_t i = first; i < pages.size(); ++i)
    ASSERT_EQ(pages[i].find("<image"), std::string::npos) << "page " << i + 1;
  std::cout << "[ figures  ] " << seconds << " s, " << pages.size() << " pages, " << first
            << " in colour\n";
}

TEST(TimeLimit, OneDrawingWithoutPaperIsDrawnWithinTheLimit) {
  // The milk truck at 1,000 mm without paper: one drawing, each of its parts' colour an image of
  // up to 36 million pixels at 300 dpi, and a quarter of a million small triangles of colour.
  // Given 8 s it ended after 37.6 s in 1.3 GB: the drawing was not paced. Now its resolution is
  // chosen for the time left (docs/colour.md, "Time limit"), or its colour left out, with a
  // warning naming the drawing.
  const JobInput input = data_file("CesiumMilkTruck/CesiumMilkTruck.gltf");
  JobOptions options;
  options.time_limit = 8;
  options.paper = "none";
  options.size_mm = 1000;
  double seconds = 0;
  const UnfoldOutcome out = run_within_limit(input, options, {.svg_pages = true}, seconds);
  ASSERT_EQ(out.documents.svg_pages.size(), 1u);
  const NetRepair* lowered = entry_of(out.net.warnings, "colour_resolution_lowered");
  const NetRepair* left_out = entry_of(out.net.warnings, "colour_left_out");
  ASSERT_TRUE((lowered == nullptr) != (left_out == nullptr)) << "one warning, for the drawing";
  const NetRepair* warning = lowered ? lowered : left_out;
  EXPECT_EQ(warning->message.find("the drawing of the net (paper none) prints "), 0u)
      << warning->message;
  EXPECT_EQ(out.documents.svg_pages[0].find("<image") != std::string::npos, lowered != nullptr);
  std::cout << "[ figures  ] " << seconds << " s: " << warning->message << "\n";
}

TEST(TimeLimit, ThePreviewBesideThePagesIsDrawnWithinTheLimit) {
  // As the service asks: the pages (PDF and SVG) and the whole net in one SVG beside them, a
  // preview coloured at 96 dpi at most. The preview was not paced: the Menger sponge given 10 s
  // ended after 22 s, 11 s of them its preview. Here the milk truck at 1,000 mm on A4.
  const JobInput input = data_file("CesiumMilkTruck/CesiumMilkTruck.gltf");
  JobOptions options;
  options.time_limit = 8;
  options.size_mm = 1000;
  double seconds = 0;
  const UnfoldOutcome out =
      run_within_limit(input, options, {.svg = true, .svg_pages = true, .pdf = true}, seconds);
  ASSERT_TRUE(out.print);
  EXPECT_GT(out.print->pages, 1);
  EXPECT_NE(out.documents.svg.find("<svg"), std::string::npos);
  std::cout << "[ figures  ] " << seconds << " s, " << out.print->pages << " pages\n";
}

}  // namespace
}  // namespace papernet::test
