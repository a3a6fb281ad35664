#include "core/io/write_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "core/io/load.h"
#include "tests/support/meshes.h"
#include "tests/support/paths.h"

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

// A face's corners as the GLB stores them (float32): the key that finds a face again after the
// loader has welded the corners and the writer has grouped the faces by material.
using CornerKey = std::array<float, 9>;
CornerKey corner_key(const Mesh& mesh, std::size_t f) {
  CornerKey key{};
  for (int k = 0; k < 3; ++k) {
    const Vec3& v = mesh.vertices[mesh.faces[f][k]];
    key[3 * k] = static_cast<float>(v.x);
    key[3 * k + 1] = static_cast<float>(v.y);
    key[3 * k + 2] = static_cast<float>(v.z);
  }
  return key;
}

TEST(MeshExport, ColouredGlbReadsBackWithItsMaterialsTexturesAndCornerColours) {
  // A textured model of four materials (two of them plain colours), one with vertex colours,
  // one textured with one material.
  for (const std::string file :
       {"CesiumMilkTruck/CesiumMilkTruck.gltf", "cubevc.glb", "Duck.glb"}) {
    SCOPED_TRACE(file);
    const std::string path = papernet::test::test_data_dir() + "/" + file;
    LoadOptions options;  // a .gltf's buffers and images beside it
    if (path.ends_with(".gltf"))
      for (const std::string& uri : gltf_external_uris(read_mesh_file(path, options.max_bytes)))
        options.external_files[uri] =
            read_mesh_file(path.substr(0, path.rfind('/') + 1) + uri, options.max_bytes);
    const LoadedMesh in = load_mesh_file(path, options);
    ASSERT_FALSE(in.colour.empty());
    const std::string glb = write_glb(in.mesh, in.colour);
    const LoadedMesh back = load_mesh(glb, MeshFormat::Glb);
    ASSERT_EQ(back.mesh.faces.size(), in.mesh.faces.size());
    const MeshColour &a = in.colour, &b = back.colour;

    // The materials as they were (faces without one would get a white one of their own), not
    // metallic; the textures' images byte for byte, with their samplers.
    const bool plain = std::any_of(a.face_materials.begin(), a.face_materials.end(),
                                   [](int m) { return m < 0; }) ||
                       a.face_materials.empty();
    ASSERT_EQ(b.materials.size(), a.materials.size() + (plain ? 1 : 0));
    for (std::size_t m = 0; m < a.materials.size(); ++m) {
      EXPECT_EQ(b.materials[m].name, a.materials[m].name);
      EXPECT_EQ(b.materials[m].texture, a.materials[m].texture);
      EXPECT_EQ(b.materials[m].alpha_mode, a.materials[m].alpha_mode);
      for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(b.materials[m].base_color[i], a.materials[m].base_color[i], 1e-12);
    }
    ASSERT_EQ(b.textures.size(), a.textures.size());
    for (std::size_t t = 0; t < a.textures.size(); ++t) {
      EXPECT_EQ(b.textures[t].bytes, a.textures[t].bytes);
      EXPECT_EQ(b.textures[t].mime_type, a.textures[t].mime_type);
      EXPECT_EQ(b.textures[t].sampler.wrap_s, a.textures[t].sampler.wrap_s);
      EXPECT_EQ(b.textures[t].sampler.min_filter, a.textures[t].sampler.min_filter);
    }
    const auto gltf = nlohmann::json::parse(glb.substr(20, u32(glb, 12)));
    for (const auto& m : gltf["materials"]) {
      EXPECT_EQ(m["pbrMetallicRoughness"]["metallicFactor"], 0);
      EXPECT_EQ(m["doubleSided"], true);
    }

    // Each face again, found by its corners: its material, and its corners' texture coordinates
    // (where its material has a texture) and colours.
    std::map<CornerKey, std::size_t> faces;
    for (std::size_t f = 0; f < in.mesh.faces.size(); ++f) faces[corner_key(in.mesh, f)] = f;
    ASSERT_EQ(faces.size(), in.mesh.faces.size()) << "two faces with the same corners";
    std::size_t textured = 0, coloured = 0;
    for (std::size_t f = 0; f < back.mesh.faces.size(); ++f) {
      const auto it = faces.find(corner_key(back.mesh, f));
      ASSERT_NE(it, faces.end()) << "face " << f << " of the GLB is not a face of the model";
      const std::size_t g = it->second;
      const int ma = a.face_materials.empty() ? -1 : a.face_materials[g];
      const int mb = b.face_materials.at(f);
      ASSERT_EQ(mb, ma < 0 ? static_cast<int>(a.materials.size()) : ma);
      if (ma >= 0 && a.materials[ma].texture >= 0) {
        ++textured;
        for (int k = 0; k < 3; ++k)
          for (int i = 0; i < 2; ++i) EXPECT_NEAR(b.uvs.at(f)[k][i], a.uvs[g][k][i], 1e-6);
      }
      if (!a.colours.empty()) {
        ++coloured;
        for (int k = 0; k < 3; ++k)
          for (int i = 0; i < 4; ++i) EXPECT_NEAR(b.colours.at(f)[k][i], a.colours[g][k][i], 1e-6);
      }
    }
    EXPECT_GT(textured + coloured, 0u);
  }
}

TEST(MeshExport, RefusesBadMeshes) {
  EXPECT_THROW(write_glb(Mesh{}), std::invalid_argument);
  Mesh bad = test::tetrahedron();
  bad.faces[0][1] = 17;
  EXPECT_THROW(write_glb(bad), std::invalid_argument);
  EXPECT_THROW(write_obj(bad), std::invalid_argument);
  // Colour that does not match the mesh.
  MeshColour colour;
  colour.face_materials = {0};
  colour.materials.emplace_back();
  EXPECT_THROW(write_glb(test::tetrahedron(), colour), std::invalid_argument);
}

}  // namespace
}  // namespace papernet
