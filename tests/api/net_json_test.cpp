#include "api/net_json.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "core/unfold/unfolding.h"
#include "tests/support/meshes.h"

namespace papernet {
namespace {

NetDocument cube_document() {
  NetDocument doc;
  doc.strategy = "TU";
  doc.mesh = test::cube();
  doc.input = {8, 12, 1, 0, 0};
  Progress quiet;
  doc.net = unfold_tabu(doc.mesh, {}, quiet).net;
  doc.piece.assign(12, 0);
  doc.pieces = {{0, "complete", 12, 0}};
  doc.repairs = {{"reoriented_faces", 1, "turned 1 face to agree with its neighbours: faces 5"}};
  doc.metrics.faces = 12;
  doc.metrics.seconds = 0.5;
  return doc;
}

TEST(NetJson, WritesTheFieldsOfTheFormat) {
  const nlohmann::json j = net_to_json(cube_document());
  EXPECT_EQ(j["format"], "papernet.net/2");
  EXPECT_EQ(j["input"]["components"], 1);
  ASSERT_EQ(j["pieces"].size(), 1u);
  EXPECT_EQ(j["pieces"][0]["component"], 0);
  EXPECT_EQ(j["pieces"][0]["result"], "complete");
  EXPECT_EQ(j["pieces"][0]["faces"], 12);
  ASSERT_EQ(j["repairs"].size(), 1u);
  EXPECT_EQ(j["repairs"][0]["code"], "reoriented_faces");
  EXPECT_EQ(j["repairs"][0]["count"], 1);
  EXPECT_EQ(j["result"], "complete");
  EXPECT_EQ(j["strategy"], "TU");
  EXPECT_EQ(j["input"]["faces"], 12);
  EXPECT_EQ(j["mesh"]["vertices"].size(), 8u);
  EXPECT_EQ(j["mesh"]["faces"][0].size(), 3u);
  ASSERT_EQ(j["net"]["faces"].size(), 12u);
  EXPECT_EQ(j["net"]["faces"][0]["points"].size(), 3u);
  EXPECT_EQ(j["net"]["faces"][0]["points"][0].size(), 2u);
  int roots = 0;
  for (const auto& f : j["net"]["faces"]) {
    roots += f["parent"] == -1 ? 1 : 0;
    EXPECT_EQ(f["piece"], 0);
  }
  EXPECT_EQ(roots, 1);
  for (const char* key : {"faces", "coverage", "aspect_ratio", "hausdorff", "overlaps", "seconds"})
    EXPECT_TRUE(j["metrics"].contains(key)) << key;
}

TEST(NetJson, ReadsBackWhatItWrote) {
  NetDocument doc = cube_document();
  doc.metrics.coverage = 0.25;
  const NetDocument back = read_net_json(write_net_json(doc));
  EXPECT_EQ(back.strategy, "TU");
  EXPECT_EQ(back.mesh.faces, doc.mesh.faces);
  EXPECT_EQ(back.net.parent, doc.net.parent);
  for (std::size_t f = 0; f < doc.net.points.size(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(back.net.points[f][k] == doc.net.points[f][k]);
  EXPECT_EQ(back.metrics.coverage, 0.25);
  EXPECT_EQ(back.piece, doc.piece);
  ASSERT_EQ(back.pieces.size(), 1u);
  EXPECT_EQ(back.pieces[0].faces, 12u);
  ASSERT_EQ(back.repairs.size(), 1u);
  EXPECT_EQ(back.repairs[0].message, doc.repairs[0].message);
  EXPECT_EQ(back.input.components, 1u);
  EXPECT_FALSE(back.metrics.aspect_ratio.has_value());
}

TEST(NetJson, RefusesOtherDocuments) {
  EXPECT_THROW(read_net_json("not json"), IOException);
  EXPECT_THROW(read_net_json(R"({"format": "other/1"})"), IOException);
  nlohmann::json j = net_to_json(cube_document());
  j["net"]["faces"].erase(0);
  EXPECT_THROW(read_net_json(j.dump()), IOException);
  j = net_to_json(cube_document());
  j["mesh"].erase("faces");
  EXPECT_THROW(read_net_json(j.dump()), IOException);
  j = net_to_json(cube_document());
  j["net"]["faces"][3]["piece"] = 1;  // names a piece the document does not have
  EXPECT_THROW(read_net_json(j.dump()), IOException);
  j = net_to_json(cube_document());
  j["format"] = "papernet.net/1";  // the old format is not read
  EXPECT_THROW(read_net_json(j.dump()), IOException);
}

// The cube with colour: per-corner UVs (one face without), vertex colours, two materials (one
// textured), one texture.
NetDocument coloured_cube() {
  NetDocument doc = cube_document();
  MeshColour& c = doc.colour;
  for (std::size_t f = 0; f < 12; ++f) {
    const double x = double(f) / 12;
    c.uvs.push_back({UV{x, 0}, UV{x + 0.05, 0.25}, UV{x, 1.0 / 3}});
    c.colours.push_back({RGBA{1, 0, 0, 1}, RGBA{0, 1, 0, 0.5}, RGBA{0, 0, x, 1}});
    c.face_materials.push_back(f < 6 ? 0 : f < 11 ? 1 : -1);
  }
  const double nan = std::nan("");
  c.uvs[11] = {UV{nan, nan}, UV{nan, nan}, UV{nan, nan}};
  c.materials = {{"logo", {1, 1, 1, 1}, 0}, {"paint", {0.8, 0.1, 0.1, 1}, -1}};
  Texture t;
  t.name = "logo.png";
  t.mime_type = "image/png";
  t.width = 256;
  t.height = 128;
  t.sampler = {33071, 10497, 9729, 9987};
  t.bytes = "not written into the document";
  c.textures = {t};
  return doc;
}

TEST(NetJson, ColourIsWrittenPerDesign) {
  const nlohmann::json j = net_to_json(coloured_cube());
  ASSERT_EQ(j["mesh"]["uvs"].size(), 12u);
  ASSERT_EQ(j["mesh"]["uvs"][1].size(), 3u);
  EXPECT_EQ(j["mesh"]["uvs"][1][1][1], 0.25);
  EXPECT_EQ(j["mesh"]["uvs"][1][0][0], 1.0 / 12);
  EXPECT_TRUE(j["mesh"]["uvs"][11].is_null());
  EXPECT_EQ(j["mesh"]["colors"][0][1], nlohmann::json::parse("[0, 1, 0, 0.5]"));
  EXPECT_EQ(j["mesh"]["face_materials"][11], -1);
  EXPECT_EQ(j["materials"][0]["texture"], 0);
  EXPECT_TRUE(j["materials"][1]["texture"].is_null());
  EXPECT_EQ(j["materials"][1]["base_color"], nlohmann::json::parse("[0.8, 0.1, 0.1, 1]"));
  EXPECT_EQ(j["textures"][0]["mime_type"], "image/png");
  EXPECT_EQ(j["textures"][0]["width"], 256);
  EXPECT_EQ(j["textures"][0]["sampler"]["wrap_s"], 33071);
  EXPECT_EQ(j.dump().find("not written"), std::string::npos);
  // Without colour, none of it.
  const nlohmann::json plain = net_to_json(cube_document());
  EXPECT_FALSE(plain["mesh"].contains("uvs"));
  EXPECT_FALSE(plain.contains("materials"));
  EXPECT_FALSE(plain.contains("textures"));
}

TEST(NetJson, ColourRoundTrips) {
  const NetDocument doc = coloured_cube();
  const std::string text = write_net_json(doc);
  const NetDocument back = read_net_json(text);
  ASSERT_EQ(back.colour.uvs.size(), 12u);
  for (std::size_t f = 0; f < 11; ++f) EXPECT_EQ(back.colour.uvs[f], doc.colour.uvs[f]);
  for (const UV& uv : back.colour.uvs[11]) EXPECT_TRUE(std::isnan(uv[0]) && std::isnan(uv[1]));
  EXPECT_EQ(back.colour.colours, doc.colour.colours);
  EXPECT_EQ(back.colour.face_materials, doc.colour.face_materials);
  ASSERT_EQ(back.colour.materials.size(), 2u);
  EXPECT_EQ(back.colour.materials[1].name, "paint");
  EXPECT_EQ(back.colour.materials[1].base_color, doc.colour.materials[1].base_color);
  EXPECT_EQ(back.colour.materials[0].texture, 0);
  EXPECT_EQ(back.colour.materials[1].texture, -1);
  ASSERT_EQ(back.colour.textures.size(), 1u);
  EXPECT_EQ(back.colour.textures[0].name, "logo.png");
  EXPECT_EQ(back.colour.textures[0].height, 128);
  EXPECT_EQ(back.colour.textures[0].sampler.min_filter, 9987);
  EXPECT_TRUE(back.colour.textures[0].bytes.empty());  // served beside the document
  EXPECT_EQ(write_net_json(back), text);
}

TEST(NetJson, RefusesColourThatDoesNotFit) {
  nlohmann::json j = net_to_json(coloured_cube());
  j["mesh"]["uvs"].erase(0);  // not one per face
  EXPECT_THROW(read_net_json(j.dump()), IOException);
  j = net_to_json(coloured_cube());
  j["mesh"]["face_materials"][0] = 2;  // no such material
  EXPECT_THROW(read_net_json(j.dump()), IOException);
  j = net_to_json(coloured_cube());
  j["materials"][1]["texture"] = 1;  // no such texture
  EXPECT_THROW(read_net_json(j.dump()), IOException);
  j = net_to_json(coloured_cube());
  j["mesh"]["uvs"][0][1] = {0.5};  // a corner of one number
  EXPECT_THROW(read_net_json(j.dump()), IOException);
}

// The cube printed on two A4 pages, tiled: its one piece spans them.
NetDocument printed_cube() {
  NetDocument doc = cube_document();
  NetPrint& print = doc.print.emplace();
  print.paper = "A4";
  print.page_width_mm = 297;
  print.page_height_mm = 210;
  print.margin_mm = 10;
  print.mm_per_unit = 200;
  print.pages = 2;
  print.layout = "tile";
  print.placements = {{0, -1, {0, -200, -200, 0, 250, 300}}};
  print.tiles = {{0, {0, 0, 277, 190}}, {1, {267, 0, 277, 190}}};
  return doc;
}

TEST(NetJson, PrintIsWrittenPerDesignAndRoundTrips) {
  const nlohmann::json j = net_to_json(printed_cube());
  const nlohmann::json& print = j["print"];
  EXPECT_EQ(print["paper"], "A4");
  EXPECT_EQ(print["page_size_mm"], nlohmann::json::parse("[297, 210]"));
  EXPECT_EQ(print["mm_per_unit"], 200);
  EXPECT_EQ(print["pages"], 2);
  EXPECT_EQ(print["layout"], "tile");
  ASSERT_EQ(print["placements"].size(), 1u);
  EXPECT_EQ(print["placements"][0]["page"], -1);
  EXPECT_EQ(print["placements"][0]["transform"],
            nlohmann::json::parse("[0, -200, -200, 0, 250, 300]"));
  EXPECT_EQ(print["tiles"][1]["window_mm"], nlohmann::json::parse("[267, 0, 277, 190]"));
  const std::string text = j.dump();
  const NetDocument back = read_net_json(text);
  ASSERT_TRUE(back.print);
  EXPECT_EQ(back.print->placements[0].transform, printed_cube().print->placements[0].transform);
  EXPECT_EQ(back.print->tiles.size(), 2u);
  EXPECT_EQ(write_net_json(back), text);
  // Nothing printed, no `print`; fit lists no tiles.
  EXPECT_FALSE(net_to_json(cube_document()).contains("print"));
  NetDocument fit = printed_cube();
  fit.print->layout = "fit";
  fit.print->placements[0].page = 1;
  fit.print->tiles.clear();
  EXPECT_FALSE(net_to_json(fit)["print"].contains("tiles"));
  EXPECT_FALSE(net_to_json(fit)["print"].contains("overview_page"));
  EXPECT_FALSE(net_to_json(fit)["print"].contains("title")) << "no title given, none written";
}

// The kit's title (the option title) round-trips; one that is not text is refused.
TEST(NetJson, TheKitsTitleRoundTrips) {
  NetDocument doc = printed_cube();
  doc.print->title = "Kitchen Duck \u00b7 1";
  const nlohmann::json j = net_to_json(doc);
  EXPECT_EQ(j["print"]["title"], "Kitchen Duck \u00b7 1");
  EXPECT_EQ(read_net_json(j.dump()).print->title, "Kitchen Duck \u00b7 1");
  nlohmann::json bad = j;
  bad["print"]["title"] = 3;
  EXPECT_THROW(read_net_json(bad.dump()), IOException);
}

// An overview of one page or more: overview_page and overview_pages, written together; an old
// document with overview_page alone has one overview page; pages the print does not have are
// refused.
TEST(NetJson, TheOverviewsPagesRoundTrip) {
  NetDocument doc = printed_cube();
  doc.print->pages = 3;
  doc.print->overview_page = 0;
  doc.print->overview_pages = 2;
  const nlohmann::json j = net_to_json(doc);
  EXPECT_EQ(j["print"]["overview_page"], 0);
  EXPECT_EQ(j["print"]["overview_pages"], 2);
  const NetDocument back = read_net_json(j.dump());
  EXPECT_EQ(back.print->overview_page, 0);
  EXPECT_EQ(back.print->overview_pages, 2);
  nlohmann::json old = j;
  old["print"].erase("overview_pages");
  EXPECT_EQ(read_net_json(old.dump()).print->overview_pages, 1);
  for (const int bad : {0, 4, -1}) {
    nlohmann::json k = j;
    k["print"]["overview_pages"] = bad;
    EXPECT_THROW(read_net_json(k.dump()), IOException) << bad;
  }
  nlohmann::json none = j;
  none["print"].erase("overview_page");
  EXPECT_THROW(read_net_json(none.dump()), IOException) << "overview pages without an overview";
}

TEST(NetJson, RefusesPlacementsOfPiecesOrPagesItDoesNotHave) {
  nlohmann::json j = net_to_json(printed_cube());
  j["print"]["placements"][0]["piece"] = 1;
  EXPECT_THROW(read_net_json(j.dump()), IOException);
  j = net_to_json(printed_cube());
  j["print"]["placements"][0]["page"] = 2;
  EXPECT_THROW(read_net_json(j.dump()), IOException);
  j = net_to_json(printed_cube());
  j["print"]["placements"][0]["transform"].erase(5);
  EXPECT_THROW(read_net_json(j.dump()), IOException);
  j = net_to_json(printed_cube());
  j["print"]["placements"].erase(0);  // not one per piece
  EXPECT_THROW(read_net_json(j.dump()), IOException);
}

}  // namespace
}  // namespace papernet
