// glTF loading: node transforms, buffers (data URI, GLB, supplied external files), refusal of
// paths on the server's disk, primitive modes and accessor bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/errors.h"
#include "core/io/load.h"
#include "tests/support/hostile_bytes.h"
#include "tests/support/meshes.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

using nlohmann::json;

using test::base64;

/// A unit square in z=0 (4 positions, 2 triangles, counter-clockwise seen from +z).
std::string square_buffer() {
  const float p[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
  std::string s(reinterpret_cast<const char*>(p), 48);
  s.append(reinterpret_cast<const char*>(idx), 12);
  return s;
}

json square_gltf(const std::string& uri, json node = json::object(), int mode = 4) {
  node["mesh"] = 0;
  return {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {node}},
      {"meshes",
       {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"mode", mode}}}}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}}}},
      {"buffers", {{{"uri", uri}, {"byteLength", 60}}}}};
}

std::string data_uri() { return "data:application/octet-stream;base64," + base64(square_buffer()); }

std::string error_of(const std::string& gltf, const LoadOptions& options = {}) {
  try {
    load_mesh(gltf, MeshFormat::Gltf, options);
  } catch (const IOException& e) {
    return e.what();
  }
  return "";
}

TEST(LoadGltf, DataUriBufferAndSniffing) {
  const std::string text = square_gltf(data_uri()).dump();
  EXPECT_EQ(sniff_format(text), MeshFormat::Gltf);
  const LoadedMesh m = load_mesh(text, MeshFormat::Unknown);
  EXPECT_EQ(m.format, MeshFormat::Gltf);
  ASSERT_EQ(m.mesh.faces.size(), 2u);
  EXPECT_EQ(m.mesh.vertices.size(), 4u);
  EXPECT_GT(face_normal(m.mesh, 0).z, 0);
}

TEST(LoadGltf, TranslationRotationScaleAreApplied) {
  // Scale x by 2, rotate 90 degrees about z, then translate by (10, 0, 0):
  // (1, 0, 0) -> (2, 0, 0) -> (0, 2, 0) -> (10, 2, 0).
  const double h = std::sqrt(0.5);
  const json node = {{"scale", {2, 1, 1}}, {"rotation", {0, 0, h, h}}, {"translation", {10, 0, 0}}};
  const LoadedMesh m = load_mesh(square_gltf(data_uri(), node).dump(), MeshFormat::Gltf);
  const Vec3 p = m.mesh.vertices[m.mesh.faces[0][1]];  // the square's (1, 0, 0)
  EXPECT_NEAR(p.x, 10, 1e-12);
  EXPECT_NEAR(p.y, 2, 1e-12);
  EXPECT_NEAR(p.z, 0, 1e-12);
}

TEST(LoadGltf, MatrixOfAParentNodeAndMirrorKeepsFacesOutward) {
  json g = square_gltf(data_uri());
  // Parent mirrors z... of a flat square nothing shows; mirror x instead and check the winding.
  g["nodes"] = {{{"children", {1}}, {"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1}}},
                {{"mesh", 0}}};
  g["scenes"] = {{{"nodes", {0}}}};
  const LoadedMesh m = load_mesh(g.dump(), MeshFormat::Gltf);
  const Vec3 p = m.mesh.vertices[m.mesh.faces[0][0]];  // the square's origin, moved to x=5
  EXPECT_DOUBLE_EQ(p.x, 5);
  // A mirror would turn the face clockwise; the loader swaps corners so it still faces +z.
  EXPECT_GT(face_normal(m.mesh, 0).z, 0);
  EXPECT_GT(face_normal(m.mesh, 1).z, 0);
}

// Regressions (docs/reliability.md): the node hierarchy was walked by recursion, so a chain of
// 50,000 nodes (a 1 MB file) overflowed the stack; and the JSON pre-pass (nlohmann's parse
// callback) was quadratic in the length of an array of objects, so parsing it took minutes.
TEST(LoadGltf, LongNodeChainsLoadWithoutRecursion) {
  json g = square_gltf(data_uri());
  const int depth = 50'000;
  json nodes = json::array();
  for (int i = 0; i + 1 < depth; ++i) nodes.push_back({{"children", {i + 1}}});
  nodes.push_back({{"mesh", 0}, {"translation", {0, 0, 1}}});
  g["nodes"] = nodes;
  const LoadedMesh m = load_mesh(g.dump(), MeshFormat::Gltf);
  ASSERT_EQ(m.mesh.faces.size(), 2u);
  EXPECT_EQ(m.mesh.vertices[0].z, 1.0);
}

TEST(LoadGltf, ExternalBufferComesOnlyFromTheSuppliedFiles) {
  const std::string text = square_gltf("square.bin").dump();
  LoadOptions with;
  with.external_files["square.bin"] = square_buffer();
  EXPECT_EQ(load_mesh(text, MeshFormat::Gltf, with).mesh.faces.size(), 2u);
  EXPECT_NE(error_of(text).find("not supplied"), std::string::npos) << error_of(text);
  EXPECT_EQ(gltf_external_uris(text), std::vector<std::string>{"square.bin"});
  EXPECT_TRUE(gltf_external_uris(square_gltf(data_uri()).dump()).empty());
}

TEST(LoadGltf, PathsOnTheServersDiskAreRefused) {
  // Even with other files supplied, and even though these paths exist or may exist on disk.
  LoadOptions options;
  options.external_files["square.bin"] = square_buffer();
  for (const std::string uri :
       {"file:///etc/passwd", "/etc/passwd", "../x.bin", "../../etc/passwd", "./../square.bin"}) {
    SCOPED_TRACE(uri);
    const std::string err = error_of(square_gltf(uri).dump(), options);
    EXPECT_FALSE(err.empty());
    EXPECT_NE(err.find("not supplied"), std::string::npos) << err;
  }
}

TEST(LoadGltf, StripAndFanAreConvertedLinesAndPointsRefusedByName) {
  // Strip 0 1 2 0 2 3 -> (0 1 2) (1 0 2) (2 0 2: a restart, skipped) (0 3 2).
  json strip = square_gltf(data_uri(), json::object(), 5);
  EXPECT_EQ(load_mesh(strip.dump(), MeshFormat::Gltf).mesh.faces.size(), 3u);
  json fan = square_gltf(data_uri(), json::object(), 6);
  fan["accessors"][1]["count"] = 4;  // 0 1 2 0 -> 2 triangles, one degenerate (0,2,0) skipped
  EXPECT_EQ(load_mesh(fan.dump(), MeshFormat::Gltf).mesh.faces.size(), 1u);
  const std::pair<int, const char*> refused[] = {
      {0, "POINTS"}, {1, "LINES"}, {2, "LINE_LOOP"}, {3, "LINE_STRIP"}};
  for (const auto& [mode, name] : refused) {
    const std::string err = error_of(square_gltf(data_uri(), json::object(), mode).dump());
    EXPECT_NE(err.find(name), std::string::npos) << err;
  }
}

TEST(LoadGltf, AccessorsThatOverrunTheirBufferViewAreRefused) {
  json g = square_gltf(data_uri());
  g["accessors"][0]["count"] = 2000000000;
  EXPECT_NE(error_of(g.dump()).find("declares 2000000000 elements"), std::string::npos)
      << error_of(g.dump());
  json h = square_gltf(data_uri());
  h["accessors"][1]["byteOffset"] = 8;
  EXPECT_NE(error_of(h.dump()).find("indices accessor"), std::string::npos) << error_of(h.dump());
  json v1 = square_gltf(data_uri());
  v1["asset"]["version"] = "1.0";
  EXPECT_FALSE(error_of(v1.dump()).empty());
}

TEST(LoadGltf, JsonFloodsAndDeepNestingAreRefusedBeforeParsing) {
  json g = square_gltf(data_uri());
  g["extras"] = std::vector<int>(3'000'000, 0);
  EXPECT_NE(error_of(g.dump()).find("more than 2000000 values"), std::string::npos);
  std::string deep = square_gltf(data_uri()).dump();
  deep.pop_back();
  deep += ",\"extras\":" + std::string(100000, '[') + std::string(100000, ']') + "}";
  EXPECT_NE(error_of(deep).find("deeper than 64"), std::string::npos) << error_of(deep);
}

TEST(LoadGltf, DracoPayloadCountsAreCheckedBeforeTinygltfDecodesThem) {
  std::ifstream in(papernet::test::test_data_dir() + "/Box_Draco.glb", std::ios::binary);
  const std::string glb((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t draco = glb.find("DRACO");
  ASSERT_NE(draco, std::string::npos);
  // A sequential stream: 11 header bytes, then the face and point counts as varints (12, 24).
  ASSERT_EQ(glb[draco + 11], 12);
  ASSERT_EQ(glb[draco + 12], 24);
  auto error = [&](std::size_t at, char value, std::size_t max_faces) {
    std::string patched = glb;
    patched[draco + at] = value;
    LoadOptions options;
    options.max_faces = max_faces;
    try {
      load_mesh(patched, MeshFormat::Glb, options);
    } catch (const IOException& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error(11, 127, 100), "drc header declares 127 faces, more than the limit of 100");
  EXPECT_EQ(error(12, 127, 100), "drc: the header declares 127 points for 12 faces");
  EXPECT_EQ(error(11, 12, 11), "drc header declares 12 faces, more than the limit of 11");
}

// Found by fuzz_upload: an accessor of a Draco primitive with an unknown componentType made
// tinygltf size its decoded buffer as about 4 GB (component size -1) before checking anything.
TEST(LoadGltf, DracoAccessorsWithoutAValidComponentTypeAreRefused) {
  std::ifstream in(papernet::test::test_data_dir() + "/Box_Draco.glb", std::ios::binary);
  const std::string glb((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_NO_THROW(load_mesh(glb, MeshFormat::Glb, {}));
  // The indices accessor (0) is 5121, the POSITION and NORMAL accessors (1, 2) are 5126; the
  // patches keep the JSON chunk's length.
  const auto patched = [&](const std::string& from, const std::string& to, int nth) {
    std::string out = glb;
    std::size_t at = out.find(from);
    for (int i = 0; i < nth; ++i) at = out.find(from, at + 1);
    EXPECT_NE(at, std::string::npos);
    return out.replace(at, from.size(), to);
  };
  const auto error = [](const std::string& bytes) {
    try {
      load_mesh(bytes, MeshFormat::Glb, {});
    } catch (const IOException& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error(patched("5126", "5127", 1)),
            "gltf: mesh 0 primitive 0: accessor 2 has no valid componentType (5120-5123, 5125 "
            "or 5126)");
  EXPECT_EQ(error(patched("5121", "5124", 0)),
            "gltf: mesh 0 primitive 0: accessor 0 has no valid componentType (5120-5123, 5125 "
            "or 5126)");
  EXPECT_EQ(error(patched("\"componentType\": 5126", "\"componentTypo\": 5126", 0)),
            "gltf: mesh 0 primitive 0: accessor 1 has no valid componentType (5120-5123, 5125 "
            "or 5126)");
}

// The glTF route of docs/reliability.md row 9: tinygltf's Draco hook converts every attribute a
// primitive names, after our pre-pass, so the pre-pass refuses a stream in which a named
// attribute is not a number type. The fuzzer's stream has a float attribute (normals) and the
// bool positions, both with unique id 0, so an id finds the float one; byte 61 gives the bool one
// id 1.
TEST(LoadGltf, DracoAttributesItNamesMustBeNumbers) {
  std::string drc = test::bool_positions_drc();
  ASSERT_EQ(drc[61], 0);
  drc[61] = 1;
  const auto gltf = [&](const json& draco_attributes) {
    const json accessor = {{"componentType", 5126}, {"count", 4}, {"type", "VEC3"}};
    json attributes = json::object();
    int next = 0;
    for (const auto& [name, id] : draco_attributes.items()) attributes[name] = next++;
    json accessors(static_cast<std::size_t>(next), accessor);
    accessors.push_back({{"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}});
    return json{{"asset", {{"version", "2.0"}}},
                {"extensionsUsed", {"KHR_draco_mesh_compression"}},
                {"extensionsRequired", {"KHR_draco_mesh_compression"}},
                {"meshes",
                 {{{"primitives",
                    {{{"attributes", attributes},
                      {"indices", next},
                      {"extensions",
                       {{"KHR_draco_mesh_compression",
                         {{"bufferView", 0}, {"attributes", draco_attributes}}}}}}}}}}},
                {"accessors", accessors},
                {"bufferViews", {{{"buffer", 0}, {"byteLength", drc.size()}}}},
                {"buffers",
                 {{{"uri", "data:application/octet-stream;base64," + base64(drc)},
                   {"byteLength", drc.size()}}}}}
        .dump();
  };
  const std::string refused =
      "drc: values of attribute 1 have data type 11, not a number type (Draco DT_INT8 to "
      "DT_FLOAT64)";
  EXPECT_EQ(error_of(gltf({{"POSITION", 1}})), refused);
  EXPECT_EQ(error_of(gltf({{"NORMAL", 1}, {"POSITION", 0}})), refused);  // positions are floats
}

TEST(LoadGltf, NoSceneTakesAllMeshes) {
  json g = square_gltf(data_uri());
  g.erase("scene");
  g.erase("scenes");
  g.erase("nodes");
  EXPECT_EQ(load_mesh(g.dump(), MeshFormat::Gltf).mesh.faces.size(), 2u);
}

TEST(LoadGltf, DuckPositionsEndWithinTheScaledAccessorBounds) {
  // Duck.glb's root node scales by 0.01; the POSITION accessor's min/max (written by the
  // exporter, read here independently of the loader) bound the raw positions.
  std::ifstream in(papernet::test::test_data_dir() + "/Duck.glb", std::ios::binary);
  const std::string glb((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  const json doc = json::parse(glb.substr(20, json_length));
  const auto& acc =
      doc["accessors"][doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()];
  double raw = 0;
  for (int c = 0; c < 3; ++c)
    raw = std::max(
        {raw, std::abs(acc["min"][c].get<double>()), std::abs(acc["max"][c].get<double>())});
  const LoadedMesh m = load_mesh(glb, MeshFormat::Unknown);
  double loaded = 0;
  for (const Vec3& p : m.mesh.vertices)
    loaded = std::max({loaded, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  EXPECT_GT(raw, 50);                        // the raw model is large...
  EXPECT_LE(loaded, raw * 0.01 * 1.000001);  // ...and loads scaled (a rotation keeps |p| bounded)
  EXPECT_GT(loaded, raw * 0.01 * 0.3);
}

}  // namespace
}  // namespace papernet
