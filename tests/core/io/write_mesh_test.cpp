#include "core/io/write_mesh.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>

#include "core/io/load.h"
#include "tests/support/meshes.h"

namespace papernet {
namespace {

std::uint32_t u32(const std::string& s, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

TEST(MeshExport, GlbContainerHoldsTheMeshExactly) {
  const Mesh mesh = test::octahedron(-0.4);
  const std::string glb = write_glb(mesh);
  ASSERT_GE(glb.size(), 20u);
  EXPECT_EQ(glb.substr(0, 4), "glTF");
  EXPECT_EQ(u32(glb, 4), 2u);
  EXPECT_EQ(u32(glb, 8), glb.size());
  const std::uint32_t json_len = u32(glb, 12);
  EXPECT_EQ(json_len % 4, 0u);
  EXPECT_EQ(glb.substr(16, 4), "JSON");
  const auto gltf = nlohmann::json::parse(glb.substr(20, json_len));
  const std::size_t bin_at = 20 + json_len;
  EXPECT_EQ(glb.substr(bin_at + 4, 4), std::string("BIN\0", 4));
  const std::uint32_t bin_len = u32(glb, bin_at);
  EXPECT_EQ(bin_at + 8 + bin_len, glb.size());
  EXPECT_EQ(gltf["buffers"][0]["byteLength"], bin_len);
  EXPECT_EQ(gltf["asset"]["version"], "2.0");
  const auto& prim = gltf["meshes"][0]["primitives"][0];
  const auto& pos = gltf["accessors"][prim["attributes"]["POSITION"].get<int>()];
  const auto& idx = gltf["accessors"][prim["indices"].get<int>()];
  ASSERT_EQ(pos["count"], mesh.vertices.size());
  ASSERT_EQ(idx["count"], 3 * mesh.faces.size());
  EXPECT_EQ(pos["min"][2], -1.0);
  EXPECT_EQ(pos["max"][0], 1.0);
  const std::string bin = glb.substr(bin_at + 8);
  const auto& pv = gltf["bufferViews"][pos["bufferView"].get<int>()];
  const auto& iv = gltf["bufferViews"][idx["bufferView"].get<int>()];
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    float p[3];
    std::memcpy(p, bin.data() + pv["byteOffset"].get<std::size_t>() + 12 * i, 12);
    EXPECT_FLOAT_EQ(p[0], static_cast<float>(mesh.vertices[i].x));
    EXPECT_FLOAT_EQ(p[1], static_cast<float>(mesh.vertices[i].y));
    EXPECT_FLOAT_EQ(p[2], static_cast<float>(mesh.vertices[i].z));
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(static_cast<int>(u32(bin, iv["byteOffset"].get<std::size_t>() + 4 * (3 * f + k))),
                mesh.faces[f][k]);
}

TEST(MeshExport, ObjReadsBackThroughTheLoader) {
  for (const auto& [name, mesh] : test::test_data_meshes()) {
    const LoadedMesh back = load_mesh(write_obj(mesh), MeshFormat::Obj);
    ASSERT_EQ(back.mesh.faces.size(), mesh.faces.size()) << name;
    ASSERT_EQ(back.mesh.vertices.size(), mesh.vertices.size()) << name;
    double area = 0, back_area = 0;
    for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
      area += face_area(mesh, f), back_area += face_area(back.mesh, f);
    EXPECT_NEAR(back_area, area, 1e-6 * area) << name;
  }
}

TEST(MeshExport, GlbReadsBackThroughTheGltfLoader) {
  for (const auto& [name, mesh] : test::test_data_meshes()) {
    const LoadedMesh back = load_mesh(write_glb(mesh), MeshFormat::Glb);
    ASSERT_EQ(back.mesh.faces.size(), mesh.faces.size()) << name;
    ASSERT_EQ(back.mesh.vertices.size(), mesh.vertices.size()) << name;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        const Vec3 a = mesh.vertices[mesh.faces[f][k]],
                   b = back.mesh.vertices[back.mesh.faces[f][k]];
        EXPECT_NEAR(norm(a - b), 0, 1e-6 * (1 + norm(a))) << name << " face " << f;
      }
  }
}

TEST(MeshExport, RefusesBadMeshes) {
  EXPECT_THROW(write_glb(Mesh{}), std::invalid_argument);
  Mesh bad = test::tetrahedron();
  bad.faces[0][1] = 17;
  EXPECT_THROW(write_glb(bad), std::invalid_argument);
  EXPECT_THROW(write_obj(bad), std::invalid_argument);
}

}  // namespace
}  // namespace papernet
