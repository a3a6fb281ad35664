#include "api/net_json.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace papernet
