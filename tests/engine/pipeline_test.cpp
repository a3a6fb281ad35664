// The engine's one pipeline (engine/pipeline.h) driven directly: the documents it writes, what it
// refuses and why, and its progress; every net it returns passes the net checker.
#include "engine/pipeline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/load.h"
#include "core/mesh/validate.h"
#include "core/unfold/net_check.h"
#include "engine/internal/steps.h"
#include "tests/support/job_input.h"

namespace papernet::test {
namespace {

JobOptions tu(std::uint64_t seed = 1) {
  JobOptions options;
  options.strategy = Strategy::TU;
  options.seed = seed;
  options.detail = {DetailMode::Full, 0};  // the mesh as given
  return options;
}

void expect_checked(const UnfoldOutcome& out) {
  const NetCheckReport check = check_pieces(out.net.mesh, out.net.net, out.net.piece);
  EXPECT_TRUE(check.ok()) << check.summary();
  const NetDocument doc = read_net_json(out.documents.net_json);
  EXPECT_EQ(doc.net.parent, out.net.net.parent);
  EXPECT_EQ(doc.mesh.faces.size(), out.net.mesh.faces.size());
}

int pdf_pages(const std::string& pdf) {
  int pages = 0;
  for (std::size_t at = 0; (at = pdf.find("/Type /Page", at)) != std::string::npos; ++at)
    if (pdf.compare(at, 12, "/Type /Pages") != 0) ++pages;
  return pages;
}

TEST(Pipeline, WritesTheDocumentsAskedForAndCountsThePrint) {
  PipelineProgress quiet;
  DocumentRequest all{.svg = true, .svg_pages = true, .pdf = true, .glb = true, .obj = true};
  JobOptions big = tu();
  big.size_mm = 300;  // the cube over several A4 sheets
  const UnfoldOutcome out = run_pipeline(data_file("Box_Draco.glb"), big, {}, all, quiet);
  expect_checked(out);
  ASSERT_TRUE(out.print);
  EXPECT_GT(out.print->pages, 1);
  EXPECT_EQ(static_cast<int>(out.documents.svg_pages.size()), out.print->pages);
  EXPECT_EQ(pdf_pages(out.documents.pdf), out.print->pages);
  EXPECT_EQ(out.print->cut_edges, 7u);  // a cube's net: 18 edges, 11 glued
  EXPECT_EQ(out.print->tabs + out.print->strips, out.print->cut_edges);
  // Several pages: the one SVG is the whole net in one drawing, not a page.
  EXPECT_NE(out.documents.svg, out.documents.svg_pages.front());
  EXPECT_EQ(out.documents.glb.substr(0, 4), "glTF");
  EXPECT_NE(out.documents.obj.find("\nf "), std::string::npos);

  JobOptions small = tu();
  small.size_mm = 40;
  const UnfoldOutcome one = run_pipeline(data_file("Box_Draco.glb"), small, {}, all, quiet);
  ASSERT_TRUE(one.print);
  EXPECT_EQ(one.print->pages, 1);
  EXPECT_EQ(one.documents.svg, one.documents.svg_pages.front());
  // Without paper: one SVG sized to the net; the PDF still on A4 sheets.
  small.paper = "none";
  const UnfoldOutcome none = run_pipeline(data_file("Box_Draco.glb"), small, {}, all, quiet);
  EXPECT_EQ(none.documents.svg_pages.size(), 1u);
  EXPECT_EQ(pdf_pages(none.documents.pdf), 1);

  // Only the net JSON: no layout is made.
  const UnfoldOutcome json_only = run_pipeline(data_file("Box_Draco.glb"), tu(), {}, {}, quiet);
  EXPECT_FALSE(json_only.print);
  EXPECT_TRUE(json_only.documents.pdf.empty());
  EXPECT_EQ(nlohmann::json::parse(json_only.documents.net_json)["format"], "papernet.net/2");
}

// The default strategy (AUTO) on the real meshes of tests/data: every net passes the net
// checker, and each is complete. On the CAD part where QQ alone gives an approximation (seed 38;
// since the uncollapse's Tabu walks end at an overlapping partner, the only one of seeds 1-40),
// AUTO gives a net of the part itself. (No tab-room pass: the nets are what is tested.)
TEST(Pipeline, TheDefaultStrategyGivesCheckedCompleteNetsOfRealMeshes) {
  PipelineProgress quiet;
  JobOptions automatic;
  automatic.tab_room_budget = 0;
  automatic.detail = {DetailMode::Full, 0};  // every face: the strategy is what is tested
  for (const char* name : {"sample.obj", "reference.obj", "mirror.ply", "testplate.glb",
                           "thingi10k_134617.stl", "thingi10k_65004.stl"}) {
    SCOPED_TRACE(name);
    const UnfoldOutcome out = run_pipeline(data_file(name), automatic, {}, {}, quiet);
    expect_checked(out);
    EXPECT_EQ(out.net.strategy, "AUTO");
    EXPECT_EQ(out.net.result, "complete");
  }
  JobOptions qq = automatic;
  qq.strategy = Strategy::QQ;
  qq.seed = automatic.seed = 38;
  const UnfoldOutcome approximate =
      run_pipeline(data_file("trimesh_ADIS16480_600.obj"), qq, {}, {}, quiet);
  expect_checked(approximate);
  EXPECT_EQ(approximate.net.result, "approximate");
  const UnfoldOutcome complete =
      run_pipeline(data_file("trimesh_ADIS16480_600.obj"), automatic, {}, {}, quiet);
  expect_checked(complete);
  EXPECT_EQ(complete.net.result, "complete");
  EXPECT_EQ(complete.net.mesh.faces.size(), 600u);
}

// Colour (docs/colour.md): per-corner UVs and the textures come through repair and unfolding
// into the document; an approximate piece says it has none; a texture that cannot be used
// leaves a net and a note.
using CornerKey = std::array<double, 9>;  // a face's corner positions, from a given corner

CornerKey corner_key(const Mesh& mesh, const std::array<int, 3>& face, int from) {
  CornerKey key;
  for (int k = 0; k < 3; ++k) {
    const Vec3 p = mesh.vertices[face[(from + k) % 3]];
    key[3 * k] = p.x;
    key[3 * k + 1] = p.y;
    key[3 * k + 2] = p.z;
  }
  return key;
}

TEST(Pipeline, TheNetCarriesEachCornersUvsAndTheTextures) {
  PipelineProgress quiet;
  const JobInput input = data_file("BoxTextured.glb");
  const LoadedMesh loaded = load_mesh(input.mesh, input.format);
  std::map<CornerKey, UV> uv_of;  // a corner (with the rest of its face) -> its UV
  for (std::size_t f = 0; f < loaded.mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      uv_of[corner_key(loaded.mesh, loaded.mesh.faces[f], k)] = loaded.colour.uvs[f][k];
  for (const JobOptions& options : {tu(), JobOptions{}}) {
    const UnfoldOutcome out = run_pipeline(input, options, {}, {}, quiet);
    expect_checked(out);
    const MeshColour& c = out.net.colour;
    ASSERT_EQ(c.uvs.size(), out.net.mesh.faces.size());
    for (std::size_t f = 0; f < c.uvs.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        const auto it = uv_of.find(corner_key(out.net.mesh, out.net.mesh.faces[f], k));
        ASSERT_NE(it, uv_of.end()) << "face " << f;
        EXPECT_EQ(c.uvs[f][k], it->second) << "face " << f << " corner " << k;
      }
    EXPECT_EQ(c.face_materials, std::vector<int>(c.uvs.size(), 0));
    ASSERT_EQ(c.textures.size(), 1u);
    EXPECT_EQ(c.textures[0].bytes, loaded.colour.textures[0].bytes);
    const nlohmann::json j = nlohmann::json::parse(out.documents.net_json);
    EXPECT_EQ(j["mesh"]["uvs"].size(), c.uvs.size());
    EXPECT_EQ(j["textures"][0]["mime_type"], "image/png");
    EXPECT_EQ(read_net_json(out.documents.net_json).colour.uvs, c.uvs);
  }
}

TEST(Pipeline, AnApproximatePieceSaysItHasNoUvs) {
  // The 600-face part QQ stops short of (seed 38), with one texture coordinate on every corner.
  JobInput input = data_file("trimesh_ADIS16480_600.obj");
  std::string obj = "vt 0.25 0.75\n";
  std::istringstream lines(input.mesh);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("f ", 0) == 0) {
      std::istringstream words(line.substr(2));
      std::string out = "f";
      for (std::string v; words >> v;) {
        out += ' ';
        out += v;
        out += "/1";
      }
      line = out;
    }
    obj += line + "\n";
  }
  input.mesh = obj;
  JobOptions qq;
  qq.strategy = Strategy::QQ;
  qq.seed = 38;
  qq.tab_room_budget = 0;
  PipelineProgress quiet;
  const UnfoldOutcome out = run_pipeline(input, qq, {}, {}, quiet);
  expect_checked(out);
  ASSERT_EQ(out.net.result, "approximate");
  ASSERT_EQ(out.net.colour.uvs.size(), out.net.mesh.faces.size());
  for (const auto& f : out.net.colour.uvs) EXPECT_TRUE(std::isnan(f[0][0]));
  EXPECT_NE(entry_of(out.net.repairs, "approximate_pieces_uncoloured"), nullptr);
}

// The Duck at the defaults folds into a coarser mesh of its own faces, without texture
// coordinates: each corner carries the model's colour nearest to it as a vertex colour
// (mesh.colors), so a viewer of the folded net shows a yellow duck with an orange beak, not a
// white one (the texture: a yellow body, an orange beak, black and white eyes).
TEST(Pipeline, AnApproximatePieceOfATexturedModelCarriesItsColoursAtItsCorners) {
  PipelineProgress quiet;
  const UnfoldOutcome out = run_pipeline(data_file("Duck.glb"), {}, {}, {.glb = true}, quiet);
  expect_checked(out);
  ASSERT_EQ(out.net.result, "approximate");
  const MeshColour& c = out.net.colour;
  // The folded mesh (mesh.glb) carries the same colours at its corners.
  const LoadedMesh folded = load_mesh(out.documents.glb, MeshFormat::Glb);
  ASSERT_EQ(folded.mesh.faces.size(), out.net.mesh.faces.size());
  ASSERT_EQ(folded.colour.colours.size(), out.net.mesh.faces.size());
  std::vector<double> reds, greens;
  for (const auto& face : c.colours)
    for (const RGBA& rgba : face) reds.push_back(rgba[0]), greens.push_back(rgba[1]);
  std::vector<double> back_reds, back_greens;
  for (const auto& face : folded.colour.colours)
    for (const RGBA& rgba : face) back_reds.push_back(rgba[0]), back_greens.push_back(rgba[1]);
  for (auto* v : {&reds, &greens, &back_reds, &back_greens}) std::sort(v->begin(), v->end());
  for (std::size_t i = 0; i < reds.size(); ++i) {  // the same colours (faces may be reordered)
    EXPECT_NEAR(back_reds[i], reds[i], 1e-6);
    EXPECT_NEAR(back_greens[i], greens[i], 1e-6);
  }
  ASSERT_EQ(c.colours.size(), out.net.mesh.faces.size());
  for (const auto& f : c.uvs) EXPECT_TRUE(std::isnan(f[0][0]));
  std::size_t corners = 0, yellow = 0, orange = 0;
  for (const auto& face : c.colours)
    for (const RGBA& rgba : face) {
      ++corners;
      for (const double x : rgba) ASSERT_TRUE(x >= 0 && x <= 1) << x;
      // Linear light: the body's yellow is about (1, 0.69, 0), the beak's orange (0.9, 0.2, 0).
      yellow += rgba[0] > 0.8 && rgba[1] > 0.4 && rgba[2] < 0.2;
      orange += rgba[0] > 0.5 && rgba[1] > 0.05 && rgba[1] < 0.4 && rgba[2] < 0.1;
    }
  EXPECT_GT(yellow, corners * 8 / 10) << yellow << " of " << corners;
  EXPECT_GT(orange, corners / 50) << orange << " of " << corners;
  for (const int m : c.face_materials) EXPECT_EQ(m, -1);
  EXPECT_NE(entry_of(out.net.repairs, "approximate_pieces_vertex_coloured"), nullptr);
}

TEST(Pipeline, ATextureThatCannotBeUsedGivesANetAndANote) {
  // BoxTextured with its PNG cut short: the GLB's image buffer view keeps its length, the
  // bytes after the PNG's first 100 are zeros.
  JobInput input = data_file("BoxTextured.glb");
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, input.mesh.data() + 12, 4);
  const nlohmann::json gltf = nlohmann::json::parse(input.mesh.substr(20, json_length));
  const nlohmann::json& view = gltf["bufferViews"][gltf["images"][0]["bufferView"].get<int>()];
  const std::size_t at = 20 + json_length + 8 + view.value("byteOffset", 0u);
  std::fill(input.mesh.begin() + long(at + 100),
            input.mesh.begin() + long(at + view["byteLength"].get<std::size_t>()), '\0');
  PipelineProgress quiet;
  const UnfoldOutcome out = run_pipeline(input, tu(), {}, {}, quiet);
  expect_checked(out);
  EXPECT_TRUE(out.net.colour.textures.empty());
  EXPECT_EQ(out.net.colour.materials.at(0).texture, -1);
  EXPECT_EQ(out.net.colour.uvs.size(), 12u);
  EXPECT_NE(entry_of(out.net.repairs, "texture_not_used"), nullptr);
}

// Three tetrahedra apart (the third smaller): three parts.
JobInput three_parts() {
  std::string obj;
  for (int k = 0; k < 3; ++k) {
    const double s = k == 2 ? 0.5 : 1, x = 3.0 * k;
    obj += "v " + std::to_string(x) + " 0 0\nv " + std::to_string(x + s) + " 0 0\nv " +
           std::to_string(x) + " " + std::to_string(s) + " 0\nv " + std::to_string(x) + " 0 " +
           std::to_string(s) + "\n";
    const int b = 4 * k + 1;
    for (const auto& f : {std::array{b, b + 2, b + 1}, std::array{b, b + 1, b + 3},
                          std::array{b + 1, b + 2, b + 3}, std::array{b + 2, b, b + 3}})
      obj += "f " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
             "\n";
  }
  return {obj, MeshFormat::Obj, {}};
}

TEST(Pipeline, EveryPartIsItsOwnPieceOrOnlyTheLargestOrStrictRefusesThem) {
  PipelineProgress quiet;
  const UnfoldOutcome all = run_pipeline(three_parts(), tu(), {}, {.svg_pages = true}, quiet);
  EXPECT_TRUE(all.net.repairs.empty());
  ASSERT_EQ(all.net.pieces.size(), 3u);
  EXPECT_EQ(all.net.input.components, 3u);
  EXPECT_EQ(all.net.mesh.faces.size(), 12u);
  const NetCheckReport check = check_pieces(all.net.mesh, all.net.net, all.net.piece);
  EXPECT_TRUE(check.ok()) << check.summary();
  for (std::size_t p = 0; p < 3; ++p) {
    EXPECT_EQ(all.net.pieces[p].faces, 4u);
    EXPECT_EQ(std::count(all.net.piece.begin(), all.net.piece.end(), int(p)), 4);
  }
  ASSERT_TRUE(all.print);
  EXPECT_EQ(all.print->cut_edges, 9u);  // a tetrahedron's net has 3 cut edges
  EXPECT_EQ(read_net_json(all.documents.net_json).pieces.size(), 3u);

  JobOptions largest = tu();
  largest.components = Components::Largest;
  const UnfoldOutcome one = run_pipeline(three_parts(), largest, {}, {}, quiet);
  ASSERT_EQ(one.net.pieces.size(), 1u);
  EXPECT_EQ(one.net.mesh.faces.size(), 4u);
  ASSERT_EQ(one.net.repairs.size(), 1u);
  EXPECT_EQ(one.net.repairs[0].code, "dropped_components");
  EXPECT_EQ(one.net.repairs[0].count, 2u);
  expect_checked(one);

  JobOptions strict = tu();
  strict.strict = true;
  try {
    run_pipeline(three_parts(), strict, {}, {}, quiet);
    FAIL() << "strict unfolded a mesh in three parts";
  } catch (const InvalidMeshException& e) {
    EXPECT_EQ(e.report().components, 3u);
    bool named = false;
    for (const MeshProblem& p : e.report().problems) named |= p.code == "several_components";
    EXPECT_TRUE(named);
  }
  strict.components = Components::Largest;
  EXPECT_EQ(run_pipeline(three_parts(), strict, {}, {}, quiet).net.pieces.size(), 1u);
}

// A ribbon wound three turns up a helix (radii 1 and 1.5, 36 steps of two triangles), as OBJ:
// its dual graph is a path, so its only edge unfolding is the ribbon laid flat, which winds round
// onto itself.
JobInput helix_ribbon() {
  std::string obj;
  constexpr int kSteps = 36;
  for (int i = 0; i <= kSteps; ++i) {
    const double t = 2 * M_PI * 3 * i / kSteps, z = 0.05 * i;
    for (const double r : {1.0, 1.5})
      obj += "v " + std::to_string(r * std::cos(t)) + " " + std::to_string(r * std::sin(t)) + " " +
             std::to_string(z) + "\n";
  }
  for (int i = 0; i < kSteps; ++i) {
    const int a = 2 * i + 1;
    obj += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 2) +
           "\nf " + std::to_string(a + 1) + " " + std::to_string(a + 3) + " " +
           std::to_string(a + 2) + "\n";
  }
  return {obj, MeshFormat::Obj, {}};
}

// A part with no net in one piece at all (the ribbon above) is unfolded in grown pieces by every
// strategy, Tabu Unfolding too (which refused it, exit 2, before), and the warning says that no
// such net exists rather than that a longer time limit may find one.
TEST(Pipeline, APartWhoseOnlyUnfoldingOverlapsIsUnfoldedInPiecesByEveryStrategy) {
  PipelineProgress quiet;
  for (const Strategy strategy : {Strategy::TU, Strategy::AUTO, Strategy::QQ}) {
    SCOPED_TRACE(static_cast<int>(strategy));
    JobOptions options = tu();
    options.strategy = strategy;
    const UnfoldOutcome out = run_pipeline(helix_ribbon(), options, {}, {.svg_pages = true}, quiet);
    EXPECT_EQ(out.net.mesh.faces.size(), 72u);
    EXPECT_GT(*std::max_element(out.net.piece.begin(), out.net.piece.end()), 0);
    expect_checked(out);
    const NetRepair* warning = entry_of(out.net.warnings, "unfolded_in_pieces");
    ASSERT_NE(warning, nullptr);
    EXPECT_EQ(warning->count, 1u);
    EXPECT_NE(warning->message.find("no overlap-free net in one piece exists for 1 part of 72 "
                                    "faces (its faces join without a loop: its dual graph is a "
                                    "tree"),
              std::string::npos)
        << warning->message;
    EXPECT_EQ(warning->message.find("longer time limit"), std::string::npos) << warning->message;
  }
}

// One defect of each kind a real model has, each in a small mesh of its own: a pinch (two
// tetrahedra sharing a vertex), an edge of three faces (a fin on a tetrahedron), a zero-area
// face (a cap closing a T-junction in a square) and a flipped face (in a tetrahedron).
const std::pair<std::string, std::string> kDefects[] = {
    {"split_pinched_vertices",
     "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv -1 0 0\nv 0 -1 0\nv 0 0 -1\n"
     "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 1 5 6\nf 1 6 7\nf 5 7 6\nf 1 7 5\n"},
    {"cut_non_manifold_edges",
     "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0.5 -1 0.5\n"
     "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 1 2 5\n"},
    {"removed_degenerate_faces",
     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0\nf 1 2 5\nf 5 2 3\nf 1 3 4\nf 1 5 3\n"},
    {"reoriented_faces",
     "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 4 1\n"},
};

// With detail auto a part with folds that prints under 10 mm across is left out, and a warning
// says how many (docs/print.md, "Detail"); the largest part never is; detail full keeps every
// part. The milk truck's 14 parts: at 60 mm its four lights (13 mm across at 200 mm) print 4 mm
// across; at 20 mm all but the body are under 10 mm.
TEST(Pipeline, DetailAutoLeavesOutPartsTooSmallToBuild) {
  PipelineProgress quiet;
  const auto parts_of = [](const UnfoldOutcome& out) {
    std::set<std::size_t> parts;
    for (const NetPiece& p : out.net.pieces) parts.insert(p.component);
    return parts.size();
  };
  const auto left_out = [](const UnfoldOutcome& out) {
    return entry_of(out.net.warnings, "small_parts_left_out");
  };
  JobOptions options;
  options.size_mm = 60;
  const UnfoldOutcome sixty =
      run_pipeline(data_file("CesiumMilkTruck/CesiumMilkTruck.gltf"), options, {}, {}, quiet);
  expect_checked(sixty);
  EXPECT_EQ(sixty.net.input.components, 14u);
  EXPECT_EQ(parts_of(sixty), 10u);
  const NetRepair* warning = left_out(sixty);
  ASSERT_NE(warning, nullptr);
  EXPECT_EQ(warning->count, 4u);
  EXPECT_NE(warning->message.find("left out 4 of 14 parts"), std::string::npos) << warning->message;
  // The colour stays with its part: every face printed has its colour.
  EXPECT_EQ(sixty.net.colour.face_materials.size(), sixty.net.mesh.faces.size());

  options.size_mm = 20;
  const UnfoldOutcome twenty =
      run_pipeline(data_file("CesiumMilkTruck/CesiumMilkTruck.gltf"), options, {}, {}, quiet);
  expect_checked(twenty);
  EXPECT_EQ(parts_of(twenty), 1u);
  warning = left_out(twenty);
  ASSERT_NE(warning, nullptr);
  EXPECT_EQ(warning->count, 13u);

  // A flat part is only cut out, and stays however small: AlphaBlendModeTest's seven decals, 5
  // and 7 mm across at 200 mm.
  const JobInput alpha = data_file("AlphaBlendModeTest/AlphaBlendModeTest.glb");
  const UnfoldOutcome decals = run_pipeline(alpha, JobOptions{}, {}, {}, quiet);
  expect_checked(decals);
  EXPECT_EQ(parts_of(decals), 19u);
  EXPECT_EQ(left_out(decals), nullptr);

  // Detail full keeps every part: at 9 mm one of AlphaBlendModeTest's parts with folds is 9.1 mm
  // across, and left out with detail auto.
  options = {};
  options.size_mm = 9;
  const UnfoldOutcome tiny = run_pipeline(alpha, options, {}, {}, quiet);
  expect_checked(tiny);
  EXPECT_EQ(parts_of(tiny), 18u);
  warning = left_out(tiny);
  ASSERT_NE(warning, nullptr);
  EXPECT_EQ(warning->count, 1u);
  options.detail = {DetailMode::Full, 0};
  const UnfoldOutcome full = run_pipeline(alpha, options, {}, {}, quiet);
  expect_checked(full);
  EXPECT_EQ(parts_of(full), 19u);
  EXPECT_EQ(left_out(full), nullptr);
}

// The lowest face of a mesh over its longest edge, in the mesh's units.
double lowest_face(const Mesh& mesh) {
  double lowest = INFINITY;
  for (const auto& t : mesh.faces) {
    const Vec3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    const double longest = std::max({norm(b - a), norm(c - b), norm(a - c)});
    lowest = std::min(lowest, norm(cross(b - a, c - a)) / longest);
  }
  return lowest;
}

// With detail auto, a sliver with no short edge (the 7/8 cube's face across a T-junction: three
// corners on a line, 283 mm long and 1e-5 mm high at 200 mm, which printed on a sheet of its
// own with labels of 1e-5 mm) has its edges flipped though nothing is collapsed: the same
// surface, faces a person can label (docs/print.md, "Detail"). Detail full keeps it.
TEST(Pipeline, DetailAutoFlipsTheEdgesOfASliverWithNoShortEdge) {
  PipelineProgress quiet;
  JobOptions options;  // detail auto, 200 mm
  const UnfoldOutcome out =
      run_pipeline(data_file("seven_eighths_cube/7_8ths_cube.stl"), options, {}, {}, quiet);
  expect_checked(out);
  EXPECT_EQ(out.net.result, "approximate");
  EXPECT_EQ(out.net.mesh.faces.size(), 24u);
  EXPECT_LT(out.net.metrics.hausdorff, 1e-9);  // the same surface
  options.detail = {DetailMode::Full, 0};
  const UnfoldOutcome full =
      run_pipeline(data_file("seven_eighths_cube/7_8ths_cube.stl"), options, {}, {}, quiet);
  expect_checked(full);
  // Millimetres per unit: the cube's side prints at 200 mm.
  const Mesh& cube = full.net.mesh;
  double lo = INFINITY, hi = -INFINITY;
  for (const Vec3& v : cube.vertices) lo = std::min(lo, v.x), hi = std::max(hi, v.x);
  const double mm = 200 / (hi - lo);
  EXPECT_GE(lowest_face(out.net.mesh) * mm, 3) << "a face printed lower than 3 mm";
  EXPECT_EQ(full.net.result, "complete");
  EXPECT_LT(lowest_face(full.net.mesh) * mm, 1e-3);
}

TEST(Pipeline, EachDefectIsRepairedAndReportedAndStrictRefusesIt) {
  PipelineProgress quiet;
  std::ostringstream all;  // every defect in one model, each part apart
  int offset = 0;
  for (const auto& [code, obj] : kDefects) {
    SCOPED_TRACE(code);
    const JobInput input{obj, MeshFormat::Obj, {}};
    const UnfoldOutcome out = run_pipeline(input, tu(), {}, {.pdf = true}, quiet);
    expect_checked(out);
    ASSERT_EQ(out.net.repairs.size(), 1u);
    EXPECT_EQ(out.net.repairs[0].code, code);
    EXPECT_EQ(out.net.repairs[0].count, 1u);
    EXPECT_FALSE(out.documents.pdf.empty());
    JobOptions strict = tu();
    strict.strict = true;
    EXPECT_THROW(run_pipeline(input, strict, {}, {}, quiet), InvalidMeshException);
    // The defect's mesh, moved apart and renumbered, into the model of all of them.
    int vertices = 0;
    std::istringstream lines(obj);
    for (std::string line; std::getline(lines, line);) {
      std::istringstream words(line);
      std::string key;
      words >> key;
      if (key == "v") {
        double x, y, z;
        words >> x >> y >> z;
        all << "v " << x + 10 * offset << " " << y << " " << z << "\n";
        ++vertices;
      } else {
        all << "f";
        for (int v; words >> v;) all << " " << v + offset;
        all << "\n";
      }
    }
    offset += vertices;
  }
  const UnfoldOutcome out = run_pipeline({all.str(), MeshFormat::Obj, {}}, tu(), {}, {}, quiet);
  expect_checked(out);
  std::set<std::string> codes;
  for (const NetRepair& r : out.net.repairs) codes.insert(r.code);
  for (const auto& [code, obj] : kDefects) EXPECT_TRUE(codes.count(code)) << code;
  EXPECT_GE(out.net.pieces.size(), 5u);
}

// A file whose every face is repaired away (one of zero area, one repeating it) is refused with
// the repairs that left nothing, not only with "no faces": the file had two.
TEST(Pipeline, AMeshWithNoFaceLeftAfterRepairIsRefusedNamingTheRepairs) {
  PipelineProgress quiet;
  const JobInput input{"v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 2 3\n", MeshFormat::Obj, {}};
  try {
    run_pipeline(input, tu(), {}, {}, quiet);
    ADD_FAILURE() << "no InvalidMeshException";
  } catch (const InvalidMeshException& e) {
    EXPECT_EQ(std::string(e.what()),
              "the mesh has no faces left after repair: removed 1 degenerate face (zero area or a "
              "repeated vertex) without opening the surface: faces 0; removed 1 duplicate face "
              "(the same three vertices as another face): faces 1");
  }
}

TEST(Pipeline, LimitsAndPrintOptionsAreRefusedByName) {
  PipelineProgress quiet;
  PipelineLimits limits;
  limits.max_faces = 100;
  EXPECT_THROW(run_pipeline(data_file("sample.obj"), tu(), limits, {}, quiet),
               LimitExceededException);
  JobOptions wide = tu();
  wide.margin_mm = 200;  // passes no validate_options: the print still names it
  try {
    run_pipeline(data_file("Box_Draco.glb"), wide, {}, {.pdf = true}, quiet);
    FAIL() << "margins wider than the paper were printed";
  } catch (const InvalidOptionException& e) {
    EXPECT_EQ(e.option(), "margin_mm");
  }
}

// The pass that makes room for glue tabs runs with tabs auto and a budget, within the budget;
// taller tabs leave more edges without room.
TEST(Pipeline, MakesRoomForTabsWithinItsBudget) {
  PipelineProgress quiet;
  const JobInput part = data_file("thingi10k_134617.stl");  // 7 cut edges without room by TU
  JobOptions options = tu();
  const UnfoldOutcome full = run_pipeline(part, options, {}, {}, quiet);
  expect_checked(full);
  ASSERT_TRUE(full.tab_room);
  EXPECT_GT(full.tab_room->blocked_before, 0u);
  EXPECT_LT(full.tab_room->blocked_after, full.tab_room->blocked_before);
  EXPECT_GT(full.tab_room->moves, 0u);
  options.tabs = TabMode::Strips;
  EXPECT_FALSE(run_pipeline(part, options, {}, {}, quiet).tab_room);
  options.tabs = TabMode::Auto;
  options.tab_room_budget = 0;
  EXPECT_FALSE(run_pipeline(part, options, {}, {}, quiet).tab_room);
  options.tab_room_budget = JobOptions{}.tab_room_budget;
  options.min_tab_height_mm = 3;  // taller tabs: more edges without room than at 2 mm
  const UnfoldOutcome taller = run_pipeline(part, options, {}, {}, quiet);
  ASSERT_TRUE(taller.tab_room);
  EXPECT_GT(taller.tab_room->blocked_before, full.tab_room->blocked_before);
  EXPECT_LT(taller.tab_room->blocked_after, taller.tab_room->blocked_before);
  expect_checked(taller);

  // A budget of 40 candidate moves on a dense mesh: spent, edges left without room, and why
  // (a leaf at a nearly flat vertex), as the command line says.
  options = tu();
  options.tab_room_budget = 40;
  const UnfoldOutcome brief = run_pipeline(data_file("sample.obj"), options, {}, {}, quiet);
  ASSERT_TRUE(brief.tab_room);
  EXPECT_GT(brief.tab_room->evaluations, 0u);
  EXPECT_LE(brief.tab_room->evaluations, 80u);  // 40 in each of the pass's two rounds
  ASSERT_GT(brief.tab_room->blocked_after, 0u);
  EXPECT_GT(brief.tab_room->leaves_without_room, 0u);
  EXPECT_LE(brief.tab_room->leaves_without_room, brief.tab_room->blocked_after);
  EXPECT_EQ(brief.tab_room->interior_vertices, 502u);
  EXPECT_LT(brief.tab_room->leaf_room_vertices, 502u);
  expect_checked(brief);
}

// Progress through every phase in order, and intermediate nets of coarser meshes with their
// documents while a progressive run works.
TEST(Pipeline, ReportsPhasesInOrderAndIntermediateNets) {
  struct Recorder : PipelineProgress {
    std::vector<std::string> phases;
    std::vector<UnfoldOutcome> intermediates;
    void report(const ProgressInfo& info) override {
      if (phases.empty() || phases.back() != info.phase) phases.push_back(info.phase);
    }
    bool wants_intermediates() const override { return true; }
    void intermediate_outcome(const UnfoldOutcome& o) override { intermediates.push_back(o); }
  } recorder;
  JobOptions qq;
  qq.tab_room_budget = 2000;  // the pass runs, briefly
  qq.detail = {DetailMode::Full, 0};
  const UnfoldOutcome out = run_pipeline(data_file("sample.obj"), qq, {}, {.svg = true}, recorder);
  expect_checked(out);
  EXPECT_EQ(out.net.result, "complete");
  const std::vector<std::string> want = {"load",       "validate", "collapse", "unfold",
                                         "uncollapse", "tabs",     "layout",   "write"};
  EXPECT_EQ(recorder.phases, want);
  ASSERT_FALSE(recorder.intermediates.empty());
  for (const UnfoldOutcome& mid : recorder.intermediates) {
    expect_checked(mid);
    EXPECT_LT(mid.net.mesh.faces.size(), 1000u);
    const auto level = nlohmann::json::parse(mid.documents.net_json)["level"];
    EXPECT_EQ(level["kind"], "intermediate");
    EXPECT_EQ(level["input_faces"], 1000);
    EXPECT_FALSE(mid.documents.svg.empty());
  }
}

// One fraction of the whole run through every phase, the print's included: never back, below 1
// until the last report, which is 1; the tab-room pass moves it from its own reports (issue 23:
// the bar was full while the pass had not started); the print, most of a typical run's time
// (docs/architecture.md, "Progress"), has most of the bar, and with colour its pages most of
// that (the bar stood at 94 % while sample.obj's coloured pages were drawn).
TEST(Pipeline, ProgressFractionNeverGoesBackAndEndsAtOne) {
  struct Recorder : PipelineProgress {
    std::vector<ProgressInfo> reports;
    void report(const ProgressInfo& info) override { reports.push_back(info); }
  } recorder;
  JobOptions options;  // AUTO: collapse, unfold, uncollapse
  options.tab_room_budget = 20'000;
  const UnfoldOutcome out =
      run_pipeline(data_file("sample.obj"), options, {}, {.svg = true, .pdf = true}, recorder);
  expect_checked(out);
  ASSERT_TRUE(out.tab_room);
  const std::vector<ProgressInfo>& reports = recorder.reports;
  ASSERT_GT(reports.size(), 8u);
  std::set<std::string> phases;
  double before = 0;
  for (std::size_t i = 0; i < reports.size(); ++i) {
    const ProgressInfo& r = reports[i];
    phases.insert(r.phase);
    EXPECT_GE(r.fraction, before) << "report " << i << ", phase " << r.phase;
    if (i + 1 < reports.size()) {
      EXPECT_LT(r.fraction, 1.0) << "report " << i << ", phase " << r.phase;
    }
    before = r.fraction;
  }
  EXPECT_EQ(reports.back().fraction, 1.0);
  EXPECT_EQ(reports.back().phase, "write");
  for (const char* phase :
       {"load", "validate", "collapse", "unfold", "uncollapse", "tabs", "layout", "write"})
    EXPECT_TRUE(phases.count(phase)) << phase;
  // The pass reports from inside (evaluations made); most of the bar lies ahead of it.
  const auto first_tabs = std::find_if(reports.begin(), reports.end(),
                                       [](const ProgressInfo& r) { return r.phase == "tabs"; });
  const auto last_tabs = std::find_if(reports.rbegin(), reports.rend(),
                                      [](const ProgressInfo& r) { return r.phase == "tabs"; });
  EXPECT_LT(first_tabs->fraction, last_tabs->fraction);
  EXPECT_LT(last_tabs->fraction, 0.5);
  EXPECT_GT(last_tabs->iterations, 0u);
  // The model is coloured: its pages, drawn one by one, move the bar over a third of it.
  ASSERT_FALSE(out.net.colour.empty());
  const auto first_write = std::find_if(reports.begin(), reports.end(),
                                        [](const ProgressInfo& r) { return r.phase == "write"; });
  EXPECT_GT(reports[reports.size() - 2].fraction - first_write->fraction, 0.3);
}

// The message of the print_too_large error `run(options)` throws (failing the test without it),
// naming `option`.
template <class Run>
std::string print_too_large(const JobOptions& options, const std::string& option, Run run) {
  try {
    run(options);
  } catch (const InvalidOptionException& e) {
    EXPECT_EQ(e.code(), "print_too_large") << e.what();
    EXPECT_EQ(e.option(), option);
    return e.what();
  }
  ADD_FAILURE() << "no print_too_large";
  return "";
}

// The number (with thousands separated by commas) of the first group of `pattern` in `message`.
double number_in(const std::string& message, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(message, m, std::regex(pattern))) {
    ADD_FAILURE() << "no \"" << pattern << "\" in: " << message;
    return 0;
  }
  std::string digits = m[1].str();
  std::erase(digits, ',');
  return std::stod(digits);
}

// A print holds the model's surface of at most 20 m², on paper at most 1,000 sheets' printable
// area (docs/print.md, "Print size"): the Duck at 100 m on A4 is refused before its unfold
// (it ran for minutes, in gigabytes), naming the size that prints; that size passes the check
// the pipeline makes, 1 % more does not. Without a print there is no bound.
TEST(PrintSize, ALargerPrintIsRefusedNamingTheSizeThatPrints) {
  const JobInput input = data_file("Duck.glb");
  PipelineProgress quiet;
  const auto pipeline = [&](const JobOptions& options) {
    run_pipeline(input, options, {}, {.pdf = true}, quiet);
  };
  engine_detail::Prepared prepared =
      engine_detail::prepare(engine_detail::load_input(input, {}, quiet), {}, quiet);
  const auto check = [&](const JobOptions& options) {
    engine_detail::check_print_size(prepared.parts, options,
                                    engine_detail::parts_print_scale(prepared.parts, options));
  };
  JobOptions options;
  options.size_mm = 100'000;
  const std::string message = print_too_large(options, "size_mm", pipeline);
  EXPECT_NE(message.find("the model's surface at 100,000 mm is "), std::string::npos) << message;
  EXPECT_GT(number_in(message, R"(at least ([\d,]+) sheets of A4)"), 400'000) << message;
  const double most =
      number_in(message, R"(at most ([\d,]+) mm prints on A4 \(option 'size_mm'\))");
  ASSERT_GT(most, 1000) << message;
  options.size_mm = most;
  EXPECT_NO_THROW(check(options));
  options.size_mm = 1.01 * most;
  print_too_large(options, "size_mm", check);

  // Small paper: its 1,000 sheets hold less than 20 m², and the message says larger paper helps.
  options.paper = "40x40mm";
  options.overlap_mm = 2;
  options.size_mm = 800;
  const std::string small = print_too_large(options, "size_mm", pipeline);
  EXPECT_NE(small.find("sheets of 40x40mm"), std::string::npos) << small;
  EXPECT_NE(small.find(", or larger paper"), std::string::npos) << small;
  options.size_mm = number_in(small, R"(at most ([\d,]+) mm prints on 40x40mm)");
  EXPECT_NO_THROW(check(options));
  options.size_mm = 1.01 * *options.size_mm;
  print_too_large(options, "size_mm", check);

  // A scale, and no paper (the SVG sized to the net): 20 m² bound it, the scale named.
  JobOptions scaled;
  scaled.paper = "none";
  scaled.scale = 10'000;
  const std::string by_scale = print_too_large(scaled, "scale", [&](const JobOptions& o) {
    run_pipeline(input, o, {}, {.svg = true}, quiet);
  });
  EXPECT_EQ(by_scale.find("sheets"), std::string::npos) << by_scale;
  scaled.scale = number_in(by_scale, R"(a scale of at most ([\d,.]+) mm per unit prints \()");
  EXPECT_NO_THROW(check(scaled));
  scaled.scale = 1.01 * *scaled.scale;
  print_too_large(scaled, "scale", check);

  // Without a print, no bound: the net's JSON of the Duck at 100 m.
  options = JobOptions{};
  options.size_mm = 100'000;
  const UnfoldOutcome out = run_pipeline(input, options, {}, {}, quiet);
  EXPECT_FALSE(out.print);
  expect_checked(out);
}

}  // namespace
}  // namespace papernet::test
