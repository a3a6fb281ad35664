// `papernet unfold` as a user runs it: exit codes, what it says, and what it writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "core/vec.h"
#include "tests/support/files.h"
#include "tests/support/paths.h"
#include "tests/support/run_program.h"
#include "tests/support/sanitized.h"
#include "tests/support/scratch_dir.h"

namespace papernet::test {
namespace {

TEST(UnfoldCli, AutoIsTheDefaultAndWritesACompleteNet) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string out = scratch / "progressive.json";
  std::string said;
  ASSERT_EQ(
      papernet("unfold " + papernet::test::test_data_dir() + "/sample.obj --detail full -o " + out,
               &said),
      0)
      << said;
  const auto j = nlohmann::json::parse(read_file(out));
  EXPECT_EQ(j["strategy"], "AUTO");
  EXPECT_EQ(j["result"], "complete");
  EXPECT_EQ(j["mesh"]["faces"].size(), 1000u);
  EXPECT_EQ(j["net"]["faces"].size(), 1000u);
  EXPECT_EQ(j["metrics"]["hausdorff"], 0.0);
  ASSERT_EQ(papernet("unfold " + papernet::test::test_data_dir() + "/mirror.ply --strategy se/mp " +
                         "--target-faces 100 -o " + out,
                     &said),
            0)
      << said;
  EXPECT_EQ(nlohmann::json::parse(read_file(out))["strategy"], "SEMP");
}

// When edges stay without room for a tab, the command says how many of them end at a leaf of
// the cut tree where no leaf can have room, and what helps; a strip-free print says nothing.
TEST(UnfoldCli, SaysWhyGlueStripsRemain) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string out = scratch / "strips.svg";
  std::string said;
  ASSERT_EQ(papernet("unfold " + papernet::test::test_data_dir() + "/sample.obj --strategy TU " +
                         "--detail full --tab-room-budget 2000 --paper none -o " + out,
                     &said),
            0)
      << said;
  std::smatch room, why;
  ASSERT_TRUE(std::regex_search(said, room, std::regex(R"(-> (\d+) cut edges without room)")))
      << said;
  ASSERT_TRUE(std::regex_search(
      said, why,
      std::regex(R"(tab room: (\d+) of the (\d+) end at a leaf of the cut tree where no leaf )"
                 R"(has room \(only (\d+) of 502 vertices)")))
      << said;
  EXPECT_EQ(why[2].str(), room[1].str());
  EXPECT_GT(std::stoi(why[1].str()), 0);
  EXPECT_LE(std::stoi(why[1].str()), std::stoi(why[2].str()));
  EXPECT_LT(std::stoi(why[3].str()), 502);
  EXPECT_NE(said.find("print larger (--size)"), std::string::npos) << said;
  ASSERT_EQ(papernet("unfold " + papernet::test::test_data_dir() + "/Box_Draco.glb --strategy TU " +
                         "--paper none -o " + out,
                     &said),
            0)
      << said;
  EXPECT_NE(said.find("-> 0 cut edges without room"), std::string::npos) << said;
  EXPECT_EQ(said.find("where no leaf has room"), std::string::npos) << said;
}

// --simplify prints a low-poly version: the Duck's 4,212 faces keep hundreds of glue strips at
// 200 mm (docs/tabs.md), its 400-face version next to none. The net is approximate, of the
// simplified mesh, and the JSON says how far that is from the input.
TEST(UnfoldCli, SimplifyPrintsALowPolyVersionWithFewerStrips) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string base = scratch / "simplify";
  std::string said;
  ASSERT_EQ(papernet("unfold " + papernet::test::test_data_dir() +
                         "/Duck.glb --simplify 400 --paper none" + " -o " + base + ".json -o " +
                         base + ".svg",
                     &said),
            0)
      << said;
  EXPECT_NE(said.find("simplified from 4212 to"), std::string::npos) << said;
  const auto j = nlohmann::json::parse(read_file(base + ".json"));
  EXPECT_EQ(j["result"], "approximate");
  EXPECT_EQ(j["input"]["faces"], 4212);
  EXPECT_LE(j["mesh"]["faces"].size(), 400u);
  EXPECT_GE(j["mesh"]["faces"].size(), 350u);
  EXPECT_GT(j["metrics"]["hausdorff"].get<double>(), 0);
  EXPECT_LT(j["metrics"]["hausdorff"].get<double>(), 0.05);
  const std::string svg = read_file(base + ".svg");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, std::regex(R"re(data-strips="(\d+)")re"))) << said;
  ASSERT_TRUE(
      std::regex_search(said, std::regex(R"(, \d+ glue tabs, )" + m[1].str() + " glue strips")))
      << said;
  EXPECT_LE(std::stoi(m[1].str()), 5) << said;
  // Without paper the SVG is one drawing, not pages.
  EXPECT_NE(said.find(".svg: one drawing of the net (paper none), "), std::string::npos) << said;
  // Not below the mesh's own face count: the mesh itself, complete.
  ASSERT_EQ(papernet("unfold " + papernet::test::test_data_dir() +
                         "/Box_Draco.glb --simplify 12 -o " + base + ".json",
                     &said),
            0)
      << said;
  EXPECT_EQ(nlohmann::json::parse(read_file(base + ".json"))["result"], "complete");
  EXPECT_EQ(papernet("unfold " + papernet::test::test_data_dir() +
                         "/Box_Draco.glb --simplify 3 -o " + base + ".json",
                     &said),
            1);
  EXPECT_NE(said.find("--detail must be auto, full, or between 4 and"), std::string::npos) << said;
}

// By default a model denser than a person can build at its size is printed with fewer, larger
// faces (docs/print.md, "Detail"): the Duck's 4,212 faces at 200 mm, with hundreds of glue
// strips and labels under a millimetre, become a few hundred, every label at least 1.5 mm. Every
// face kept (--detail full) prints, with a warning in the result.
TEST(UnfoldCli, DetailAutoPrintsWhatAPersonCanBuild) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string base = scratch / "detail";
  std::string said;
  // A limit the job never meets (3 s here): sanitized, with another test beside it, the job can
  // come near the default 60 s and end its search sooner. Line art: colour is no part of what
  // this test checks (faces, strips, labels), and was half the job's time under ASan.
  ASSERT_EQ(
      papernet("unfold " + papernet::test::test_data_dir() +
                   "/Duck.glb --time-limit 600 --colour none" + papernet::test::kLightMergeFlag +
                   " -o " + base + ".json -o " + base + ".pdf",
               &said),
      0)
      << said;
  auto j = nlohmann::json::parse(read_file(base + ".json"));
  EXPECT_EQ(j["detail"]["mode"], "auto");
  EXPECT_EQ(j["detail"]["faces"], j["mesh"]["faces"].size());
  EXPECT_LT(j["mesh"]["faces"].size(), 1500u);
  EXPECT_GT(j["mesh"]["faces"].size(), 300u);
  EXPECT_EQ(j["result"], "approximate");
  EXPECT_GT(j["metrics"]["hausdorff"].get<double>(), 0);
  EXPECT_TRUE(j["warnings"].empty());
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      said, m, std::regex(R"((\d+) glue strips, .*smallest label ([0-9.]+) mm \((\d+) under)")))
      << said;
  EXPECT_LE(std::stoi(m[1].str()), 20) << said;  // 257 with every face
  EXPECT_GE(std::stod(m[2].str()), 1.5) << said;
  EXPECT_EQ(m[3].str(), "0") << said;
  ASSERT_EQ(papernet("unfold " + papernet::test::test_data_dir() +
                         "/Duck.glb --detail full --tab-room-budget 0 -o " + base + ".json",
                     &said),
            0)
      << said;
  j = nlohmann::json::parse(read_file(base + ".json"));
  EXPECT_EQ(j["detail"]["mode"], "full");
  EXPECT_EQ(j["mesh"]["faces"].size(), 4212u);
  ASSERT_EQ(j["warnings"].size(), 1u) << j["warnings"];
  EXPECT_EQ(j["warnings"][0]["code"], "detail_unbuildable");
  // The command line says it too, as it says what it repaired.
  EXPECT_NE(said.find("Duck.glb: warning: 4212 faces printed where a person can build about"),
            std::string::npos)
      << said;
}

// A CAD part of slivers and small features (thingi10k 65004): by area it is buildable at 810 of
// its 1,466 faces, which left 290 labels under 1.5 mm on edges of a millimetre or two. Detail auto
// collapses on while edges print under 3 mm, moving the surface at most 3 mm.
TEST(UnfoldCli, DetailAutoCollapsesShortEdgesOfACadPart) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string base = scratch / "detail_cad";
  std::string said;
  ASSERT_EQ(papernet("unfold " + papernet::test::test_data_dir() + "/thingi10k_65004.stl -o " +
                         base + ".json -o " + base + ".pdf",
                     &said),
            0)
      << said;
  const auto j = nlohmann::json::parse(read_file(base + ".json"));
  EXPECT_EQ(j["detail"]["mode"], "auto");
  EXPECT_LT(j["mesh"]["faces"].size(), 500u);
  const double mm_per_unit = j["print"]["mm_per_unit"].get<double>();
  // The net's edges as printed: few under 3 mm (each cut edge is drawn twice, both counted).
  std::size_t edges = 0, short_edges = 0;
  for (const auto& face : j["net"]["faces"]) {
    const auto& p = face["points"];
    for (int i = 0; i < 3; ++i) {
      const double dx = p[i][0].get<double>() - p[(i + 1) % 3][0].get<double>();
      const double dy = p[i][1].get<double>() - p[(i + 1) % 3][1].get<double>();
      ++edges;
      if (std::hypot(dx, dy) * mm_per_unit < 3) ++short_edges;
    }
  }
  EXPECT_LT(short_edges * 20, edges) << short_edges << " of " << edges;  // 714 of 2,430 before
  std::smatch m;
  ASSERT_TRUE(std::regex_search(said, m, std::regex(R"(smallest label [0-9.]+ mm \((\d+) under)")))
      << said;
  // 290 before the short-edge rule; 4 before a thin face's side took its edge's tab (0 since).
  EXPECT_LE(std::stoi(m[1].str()), 2) << said;
}

// `papernet unfold` of a file of tests/data with `options`, to JSON and to `drawing` (".pdf",
// ".svg"): the glue strips and the labels under 1.5 mm it reports, and the JSON.
struct DetailRun {
  int strips = -1, small_labels = -1;
  nlohmann::json net;
};
DetailRun run_detail(const std::string& file, const std::string& options,
                     const std::string& drawing) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string base = scratch / "detail";
  std::string said;
  DetailRun run;
  EXPECT_EQ(papernet("unfold " + papernet::test::test_data_dir() + "/" + file + " " + options +
                         " -o " + base + ".json -o " + base + drawing,
                     &said),
            0)
      << said;
  std::smatch m;
  if (!std::regex_search(
          said, m, std::regex(R"((\d+) glue strips.*smallest label [0-9.]+ mm \((\d+) under)"))) {
    ADD_FAILURE() << "no glue strips or labels said: " << said;
    return run;
  }
  run.strips = std::stoi(m[1].str());
  run.small_labels = std::stoi(m[2].str());
  run.net = nlohmann::json::parse(read_file(base + ".json"));
  return run;
}

// The milk truck's tyres and axles are small parts with edges printed under 3 mm. When a sixth of
// the faces at once would move a part more than 3 mm, detail auto collapses fewer at a time: the
// truck prints with no glue strip (13 when such a step ended the collapse). Its labels under
// 1.5 mm: none while labels could hang past their piece's outline (44 did), 17 since they must
// print on their piece, on parts of slivers under 1.5 mm wide (docs/print.md, "Labels"). Those
// parts are thin plates (the closed ones 0.3 and 0.5 mm thick at 200 mm, by twice their volume
// over their area), each printed since as one layer of card, one of its sides: 3 labels; 1 since
// labels on their glue tab sit low where a tall tab is widest, none since a label led away from
// its edge may also read across it, along a narrow strip that ends there (docs/print.md, "Labels").
TEST(UnfoldCli, DetailAutoCollapsesSmallPartsInSmallerStepsNearTheDistance) {
  const DetailRun run = run_detail("CesiumMilkTruck/CesiumMilkTruck.gltf", "--colour none", ".pdf");
  EXPECT_EQ(run.strips, 0);
  EXPECT_EQ(run.small_labels, 0);
  EXPECT_EQ(run.net["detail"]["mode"], "auto");
  EXPECT_LT(run.net["detail"]["faces"].get<int>(), 3624);
  // No closed part of the printed mesh is thinner than 1 mm at the print's scale.
  const auto& vertices = run.net["mesh"]["vertices"];
  const auto& faces = run.net["mesh"]["faces"];
  const double scale = run.net["print"]["mm_per_unit"].get<double>();
  std::vector<int> part(vertices.size());
  std::iota(part.begin(), part.end(), 0);
  const std::function<int(int)> root = [&](int v) {
    return part[v] == v ? v : part[v] = root(part[v]);
  };
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) part[root(f[k].get<int>())] = root(f[(k + 1) % 3].get<int>());
  std::map<int, double> area, volume;
  std::map<std::pair<int, int>, int> sides;  // each edge's faces, to find the closed parts
  std::map<int, bool> open;
  for (const auto& f : faces) {
    std::array<papernet::Vec3, 3> p;
    for (int k = 0; k < 3; ++k) {
      const auto& v = vertices[f[k].get<int>()];
      p[k] = {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
      const int a = f[k].get<int>(), b = f[(k + 1) % 3].get<int>();
      ++sides[{std::min(a, b), std::max(a, b)}];
    }
    const int r = root(f[0].get<int>());
    area[r] += 0.5 * norm(cross(p[1] - p[0], p[2] - p[0])) * scale * scale;
    volume[r] += dot(p[0], cross(p[1], p[2])) / 6 * scale * scale * scale;
  }
  for (const auto& [edge, n] : sides)
    if (n == 1) open[root(edge.first)] = true;
  int closed = 0;
  for (const auto& [r, a] : area) {
    if (open[r]) continue;
    ++closed;
    EXPECT_GE(2 * volume[r] / a, 1.0) << "a closed part " << 2 * volume[r] / a << " mm thick";
  }
  EXPECT_GT(closed, 5);
}

// A CAD part with 24 holes through it under 2 mm across, and slivers along its edges (trimesh
// ADIS16480): the collapse for short edges got stuck at 380 faces with 32 labels under 1.5 mm and
// 3 glue strips. Detail auto plugs the small tunnels and flips the slivers' edges, and goes on
// (7 labels under 1.5 mm left, 5 since the tab and leader placements of 2026-11-29, 3 since
// short edges are collapsed themselves where the collapse stops, 2 since leaders may bend, 1
// since they may be routed over the piece's faces, none since a legible label in the way of a
// small one moves for it).
TEST(UnfoldCli, DetailAutoPlugsSmallTunnelsAndThickensSlivers) {
  const DetailRun run = run_detail("trimesh_ADIS16480_600.obj", "", ".svg");
  EXPECT_EQ(run.strips, 0);
  EXPECT_EQ(run.small_labels, 0);
  EXPECT_LT(run.net["detail"]["faces"].get<int>(), 320);
  // Genus from V - E + F = 2 - 2g of the printed mesh (closed, one part).
  const long v = static_cast<long>(run.net["mesh"]["vertices"].size());
  const long f = static_cast<long>(run.net["mesh"]["faces"].size());
  EXPECT_LT((2 - (v - 3 * f / 2 + f)) / 2, 10);
}

// A mistake in the command: exit 1, the message naming it on the first line, then the usage
// line and where the options are listed (the whole list, 80 lines, scrolled the message off the
// screen); --help lists them. (Until 2026-12-05 the output was /dev/null, which the command
// refuses as an output of no known type, so the exit code said nothing of the options.)
TEST(UnfoldCli, BadStrategyOrTargetExitsOne) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string mesh =
      papernet::test::test_data_dir() + "/sample.obj -o " + std::string(scratch / "bad.json");
  std::string said;
  EXPECT_EQ(papernet("unfold " + mesh + " --strategy QX", &said), 1);
  EXPECT_EQ(said.rfind("papernet unfold: ", 0), 0u) << said;
  EXPECT_NE(said.substr(0, said.find('\n')).find("QX"), std::string::npos) << said;
  EXPECT_NE(said.find("papernet unfold --help lists every option"), std::string::npos) << said;
  EXPECT_EQ(std::count(said.begin(), said.end(), '\n'), 3) << said;
  EXPECT_EQ(papernet("unfold " + mesh + " --target-faces 0", &said), 1);
  EXPECT_NE(said.substr(0, said.find('\n')).find("target"), std::string::npos) << said;
  EXPECT_EQ(papernet("unfold --help", &said), 0);
  EXPECT_EQ(said.rfind("usage: papernet unfold FILE", 0), 0u) << said;
  EXPECT_NE(said.find("--strategy AUTO|QQ|SEMP|SEQ|TU"), std::string::npos) << said;
  EXPECT_NE(said.find("--overview [yes|no]"), std::string::npos) << said;
}

// A mesh with faults is repaired, and the command says what it repaired; with --strict the
// command refuses it (exit 2 with the validator's reason), never writing a net.
TEST(UnfoldCli, RepairsWhatItCanAndStrictRefusesIt) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string obj = scratch / "degenerate.obj";
  // A tetrahedron plus a zero-area face glued to one of its edges (also non-manifold).
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 2 0 0\n"
                        "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 1 2 5\n";
  const std::string out = scratch / "degenerate.json";
  std::string said;
  for (const char* strategy : {"QQ", "TU"}) {
    std::remove(out.c_str());
    EXPECT_EQ(papernet("unfold " + obj + " --strategy " + strategy + " --strict -o " + out, &said),
              2)
        << said;
    EXPECT_NE(said.find("cannot be unfolded: "), std::string::npos) << said;
    EXPECT_NE(said.find("degenerate"), std::string::npos) << said;
    EXPECT_FALSE(std::ifstream(out).good()) << "no net may be written";
    ASSERT_EQ(papernet("unfold " + obj + " --strategy " + strategy + " -o " + out, &said), 0)
        << said;
    EXPECT_NE(said.find("repaired: removed 1 degenerate face"), std::string::npos) << said;
    EXPECT_NE(said.find("pieces=1 repairs=1"), std::string::npos) << said;
    const auto j = nlohmann::json::parse(read_file(out));
    EXPECT_EQ(j["repairs"][0]["code"], "removed_degenerate_faces");
    EXPECT_EQ(j["mesh"]["faces"].size(), 4u);
  }
}

// The page summary says "no edge labels" when none is printed, not "smallest label 0 mm": with
// --labels no, and for a net of one piece (a single face: nothing glued).
TEST(UnfoldCli, APrintWithoutLabelsSaysSoInItsSummary) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string face = scratch / "face.obj", out = scratch / "out.svg";
  {
    std::ofstream obj(face);
    obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  }
  for (const std::string& run : {face, test_data_dir() + "/sample.obj --labels no"}) {
    std::string said;
    ASSERT_EQ(papernet("unfold " + run + " -o " + out, &said), 0) << said;
    EXPECT_NE(said.find(" cut edges without glue, no edge labels\n"), std::string::npos) << said;
    EXPECT_EQ(said.find("smallest label"), std::string::npos) << said;
  }
  std::string said;
  ASSERT_EQ(papernet("unfold " + test_data_dir() + "/sample.obj -o " + out, &said), 0) << said;
  EXPECT_NE(said.find(" cut edges without glue, smallest label "), std::string::npos) << said;
}

// `--title` names the kit: the PDF's title, and every page's line ("Kitchen Duck \u00b7 page k of
// n"), read back from the PDF by poppler.
TEST(UnfoldCli, TheTitleNamesThePdfAndEveryPage) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string pdf = scratch / "kit.pdf", json = scratch / "kit.json";
  std::string said;
  ASSERT_EQ(papernet("unfold " + test_data_dir() + "/sample.obj --title 'Kitchen Duck' -o " + pdf +
                         " -o " + json + " -o " + (scratch / "kit.svg"),
                     &said),
            0)
      << said;
  // The net JSON says it, for a storefront drawing its own sheets; each SVG page's <title> is
  // its line (what a browser's tab shows of the page).
  const auto net = nlohmann::json::parse(read_file(json));
  EXPECT_EQ(net["print"]["title"], "Kitchen Duck");
  const int svgs = net["print"]["pages"].get<int>();
  for (int k = 1; k <= svgs; ++k)
    EXPECT_NE(read_file(scratch / ("kit-" + std::to_string(k) + ".svg"))
                  .find("<title>Kitchen Duck \u00b7 page " + std::to_string(k) + " of " +
                        std::to_string(svgs)),
              std::string::npos)
        << "page " << k;
  // Without paper, the one drawing's <title> is the title.
  const std::string whole = scratch / "whole.svg";
  ASSERT_EQ(papernet("unfold " + test_data_dir() +
                         "/sample.obj --title 'Kitchen Duck' --paper none -o " + whole,
                     &said),
            0)
      << said;
  EXPECT_NE(read_file(whole).find("<title>Kitchen Duck</title>"), std::string::npos);
  if (std::system("command -v pdfinfo >/dev/null 2>&1 && command -v pdftotext >/dev/null 2>&1"))
    GTEST_SKIP() << "pdfinfo or pdftotext missing: install poppler-utils";
  std::string info, text;
  ASSERT_EQ(run_command("pdfinfo " + pdf, &info), 0) << info;
  EXPECT_NE(info.find("Title:           Kitchen Duck\n"), std::string::npos) << info;
  const std::smatch pages = [&] {
    std::smatch m;
    std::regex_search(info, m, std::regex("Pages: +(\\d+)"));
    return m;
  }();
  ASSERT_FALSE(pages.empty()) << info;
  const int n = std::stoi(pages[1]);
  EXPECT_GT(n, 1);
  ASSERT_EQ(run_command("pdftotext " + pdf + " -", &text), 0);
  for (int k = 1; k <= n; ++k) {
    EXPECT_NE(
        text.find("Kitchen Duck \u00b7 page " + std::to_string(k) + " of " + std::to_string(n)),
        std::string::npos)
        << "page " << k;
  }
  // Refused with the option named, as any bad option (exit 1): a title of 81 characters.
  ASSERT_EQ(papernet("unfold " + test_data_dir() + "/sample.obj --title " + std::string(81, 'x') +
                         " -o " + pdf,
                     &said),
            1)
      << said;
  EXPECT_NE(said.find("--title: at most 80 characters (81 given)"), std::string::npos) << said;
}

// With no overlap-free net in one piece within the time limit (Tabu Unfolding given a millisecond
// for a CAD part of 1,466 faces), the command still writes a net, in pieces grown from single
// faces: exit 0, the warning on stderr, grown=1 in the summary line.
TEST(UnfoldCli, WithNoNetInOnePieceWritesGrownPiecesAndSaysSo) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string out = scratch / "grown.json";
  std::string said;
  ASSERT_EQ(papernet("unfold " + test_data_dir() + "/thingi10k_65004.stl -o " + out +
                         " --strategy TU --detail full --time-limit 0.001",
                     &said),
            0)
      << said;
  EXPECT_NE(said.find("thingi10k_65004.stl: warning: no overlap-free net in one piece within the "
                      "time limit for 1 part of 1466 faces"),
            std::string::npos)
      << said;
  EXPECT_NE(said.find(" grown=1 check=ok"), std::string::npos) << said;
  const auto j = nlohmann::json::parse(read_file(out));
  EXPECT_EQ(j["result"], "complete");
  EXPECT_GT(j["pieces"].size(), 1u);
  std::size_t grown = 0;
  for (const auto& w : j["warnings"])
    if (w["code"] == "unfolded_in_pieces") grown = w["count"].get<std::size_t>();
  EXPECT_EQ(grown, 1u) << j["warnings"];
}

// A model that is a folder: a .gltf read with the buffer beside it, an OBJ with its material
// library; a .gltf whose buffer is missing is refused naming it.
TEST(UnfoldCli, ReadsTheFilesBesideALocalModel) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string out = scratch / "local.json";
  std::string said;
  ASSERT_EQ(
      papernet("unfold " + papernet::test::test_data_dir() +
                   "/CesiumMilkTruck/CesiumMilkTruck.gltf --strategy TU --detail full -o " + out,
               &said),
      0)
      << said;
  const auto j = nlohmann::json::parse(read_file(out));
  EXPECT_EQ(j["mesh"]["faces"].size(), 3624u);  // 2,856 and the wheels twice more (node instances)
  EXPECT_GT(j["pieces"].size(), 10u) << "one piece per part of the truck";
  EXPECT_EQ(j["input"]["components"], j["pieces"].size());

  const std::filesystem::path dir = scratch.path() / "local_models";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(
      papernet::test::test_data_dir() + "/CesiumMilkTruck/CesiumMilkTruck.gltf", dir / "truck.gltf",
      std::filesystem::copy_options::overwrite_existing);
  EXPECT_EQ(papernet("unfold " + (dir / "truck.gltf").string() + " -o " + out, &said), 2);
  EXPECT_NE(said.find("CesiumMilkTruck0.bin"), std::string::npos) << said;

  std::filesystem::copy_file(papernet::test::test_data_dir() + "/sample.obj", dir / "fuze.obj",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir / "fuze.obj.mtl") << "newmtl a-super-duper-material\nKd 0.8 0.2 0.1\n";
  EXPECT_EQ(papernet("unfold " + (dir / "fuze.obj").string() + " --strategy TU -o " + out, &said),
            0)
      << said;
}

// A folder given for the model: its one model file, with the files that file names (the glTF
// folder as downloaded); none or several, exit 2 with what the folder holds.
TEST(UnfoldCli, ReadsTheOneModelOfAFolder) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::string out = scratch / "folder.json";
  std::string said;
  ASSERT_EQ(papernet("unfold " + papernet::test::test_data_dir() +
                         "/CesiumMilkTruck --strategy TU --detail full -o " + out,
                     &said),
            0)
      << said;
  const auto j = nlohmann::json::parse(read_file(out));
  EXPECT_EQ(j["mesh"]["faces"].size(), 3624u);
  EXPECT_FALSE(j["textures"].empty()) << "the texture beside the .gltf was read";

  const std::filesystem::path empty = scratch.path() / "empty";
  std::filesystem::create_directories(empty);
  std::ofstream(empty / "notes.txt") << "no model here\n";
  EXPECT_EQ(papernet("unfold " + empty.string() + " -o " + out, &said), 2);
  EXPECT_NE(said.find("holds no model file"), std::string::npos) << said;

  const std::filesystem::path two = scratch.path() / "two";
  std::filesystem::create_directories(two);
  for (const char* name : {"sample.obj", "reference.obj"})
    std::filesystem::copy_file(papernet::test::test_data_dir() + "/" + name, two / name,
                               std::filesystem::copy_options::overwrite_existing);
  EXPECT_EQ(papernet("unfold " + two.string() + " -o " + out, &said), 2);
  EXPECT_NE(said.find("2 model files (reference.obj, sample.obj)"), std::string::npos) << said;
}

// The textures of a local model: a .gltf's image and an OBJ's map_Kd are read from beside the
// model and written beside the net JSON (OUT.texture-K.png).
TEST(UnfoldCli, WritesTheTexturesBesideTheJson) {
  const ScratchDir scratch("papernet_unfold_cli");
  const std::filesystem::path& dir = scratch.path();
  const std::string data = papernet::test::test_data_dir();
  std::string said;
  const std::filesystem::path out = dir / "truck.json";
  ASSERT_EQ(papernet("unfold " + data + "/CesiumMilkTruck/CesiumMilkTruck.gltf --strategy TU " +
                         "--tab-room-budget 0 -o " + out.string(),
                     &said),
            0)
      << said;
  const auto j = nlohmann::json::parse(read_file(out));
  // Its two glTF textures repeat one image with one sampler: one texture.
  ASSERT_EQ(j["textures"].size(), 1u);
  EXPECT_EQ(j["mesh"]["uvs"].size(), j["mesh"]["faces"].size());
  EXPECT_EQ(read_file(dir / "truck.texture-0.png"),
            read_file(data + "/CesiumMilkTruck/CesiumMilkTruck.png"));

  // An OBJ (the fuze, which has texture coordinates) with an MTL whose map_Kd is that PNG.
  std::filesystem::copy_file(data + "/sample.obj", dir / "fuze.obj");
  std::filesystem::copy_file(data + "/CesiumMilkTruck/CesiumMilkTruck.png", dir / "paint.png");
  std::ofstream(dir / "fuze.mtl") << "newmtl paint\nKd 0.8 0.2 0.1\nmap_Kd paint.png\n";
  std::string fuze = read_file(dir / "fuze.obj");
  fuze.replace(fuze.find("mtllib ./fuze.obj.mtl"), 21, "mtllib fuze.mtl");
  fuze.replace(fuze.find("usemtl a-super-duper-material"), 29, "usemtl paint");
  std::ofstream(dir / "fuze.obj", std::ios::binary) << fuze;
  ASSERT_EQ(papernet("unfold " + (dir / "fuze.obj").string() + " --strategy TU -o " +
                         (dir / "fuze.json").string(),
                     &said),
            0)
      << said;
  const auto k = nlohmann::json::parse(read_file(dir / "fuze.json"));
  ASSERT_EQ(k["materials"].size(), 1u);
  EXPECT_EQ(k["materials"][0]["texture"], 0);
  EXPECT_EQ(read_file(dir / "fuze.texture-0.png"), read_file(dir / "paint.png"));
}

}  // namespace
}  // namespace papernet::test
