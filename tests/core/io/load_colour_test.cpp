// Colour on load (docs/colour.md): per-corner texture coordinates as the file's accessors hold
// them, materials and their textures, vertex colours; what happens to a texture that cannot be
// used; per-corner data through welding and repair.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>

#include "core/errors.h"
#include "core/io/image.h"
#include "core/io/load.h"
#include "core/mesh/colour.h"
#include "core/mesh/repair.h"
#include "tests/support/files.h"
#include "tests/support/meshes.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

using nlohmann::json;

using test::read_file;

/// A GLB's JSON and BIN chunks, read here without the loader.
struct Glb {
  json doc;
  std::string bin;
};

Glb split_glb(const std::string& bytes) {
  std::uint32_t json_length = 0, bin_length = 0;
  std::memcpy(&json_length, bytes.data() + 12, 4);
  const std::size_t bin_at = 20 + json_length;
  std::memcpy(&bin_length, bytes.data() + bin_at, 4);
  return {json::parse(bytes.substr(20, json_length)), bytes.substr(bin_at + 8, bin_length)};
}

/// A GLB of `doc` with `bin` as its BIN chunk (both padded to 4 bytes, as glTF 2.0 §4.4 asks).
std::string join_glb(const json& doc, std::string bin) {
  std::string text = doc.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  bin.append((4 - bin.size() % 4) % 4, '\0');
  const auto u32 = [](std::size_t v) {
    const auto w = std::uint32_t(v);
    std::string out(4, '\0');
    std::memcpy(out.data(), &w, 4);
    return out;
  };
  return "glTF" + u32(2) + u32(28 + text.size() + bin.size()) + u32(text.size()) + "JSON" + text +
         u32(bin.size()) + std::string("BIN\0", 4) + bin;
}

/// The bytes of buffer view `index`.
std::string view_bytes(const Glb& glb, int index) {
  const json& v = glb.doc["bufferViews"][index];
  return glb.bin.substr(v.value("byteOffset", 0u), v["byteLength"].get<std::size_t>());
}

/// A float VEC2 accessor's values, read straight from the buffer.
std::vector<UV> vec2_accessor(const Glb& glb, int index) {
  const json& a = glb.doc["accessors"][index];
  const json& v = glb.doc["bufferViews"][a["bufferView"].get<int>()];
  const std::size_t stride = v.value("byteStride", 8u);
  const std::size_t at = v.value("byteOffset", 0u) + a.value("byteOffset", 0u);
  std::vector<UV> out(a["count"].get<std::size_t>());
  for (std::size_t i = 0; i < out.size(); ++i) {
    float uv[2];
    std::memcpy(uv, glb.bin.data() + at + i * stride, 8);
    out[i] = {uv[0], uv[1]};
  }
  return out;
}

std::vector<std::uint16_t> ushort_accessor(const Glb& glb, int index) {
  const json& a = glb.doc["accessors"][index];
  const json& v = glb.doc["bufferViews"][a["bufferView"].get<int>()];
  std::vector<std::uint16_t> out(a["count"].get<std::size_t>());
  std::memcpy(out.data(), glb.bin.data() + v.value("byteOffset", 0u) + a.value("byteOffset", 0u),
              out.size() * 2);
  return out;
}

const std::string kBoxTextured = papernet::test::test_data_dir() + "/BoxTextured.glb";

/// BoxTextured's PNG (CesiumLogoFlat.png) as the file holds it.
std::string box_png() {
  const Glb glb = split_glb(read_file(kBoxTextured));
  return view_bytes(glb, glb.doc["images"][0]["bufferView"].get<int>());
}

TEST(LoadColour, BoxTexturedUvsAreTheAccessorsValuesPerCorner) {
  const std::string bytes = read_file(kBoxTextured);
  const Glb glb = split_glb(bytes);
  const json& prim = glb.doc["meshes"][0]["primitives"][0];
  const std::vector<UV> uv = vec2_accessor(glb, prim["attributes"]["TEXCOORD_0"].get<int>());
  const std::vector<std::uint16_t> index = ushort_accessor(glb, prim["indices"].get<int>());
  const LoadedMesh loaded = load_mesh(bytes, MeshFormat::Glb);
  ASSERT_EQ(loaded.mesh.faces.size(), 12u);
  ASSERT_EQ(loaded.colour.uvs.size(), 12u);
  // Welding merged the 24 split vertices into 8; each corner kept the coordinates of its own.
  EXPECT_EQ(loaded.mesh.vertices.size(), 8u);
  for (std::size_t f = 0; f < 12; ++f)
    for (int k = 0; k < 3; ++k) {
      const UV& expected = uv[index[3 * f + std::size_t(k)]];
      EXPECT_EQ(loaded.colour.uvs[f][k], expected) << "face " << f << " corner " << k;
      EXPECT_EQ(loaded.raw_faces[f][k], int(index[3 * f + std::size_t(k)]));
    }
  ASSERT_EQ(loaded.colour.materials.size(), 1u);
  EXPECT_EQ(loaded.colour.materials[0].name, "Texture");
  EXPECT_EQ(loaded.colour.materials[0].texture, 0);
  EXPECT_EQ(loaded.colour.materials[0].base_color, (RGBA{1, 1, 1, 1}));
  EXPECT_EQ(loaded.colour.face_materials, std::vector<int>(12, 0));
  ASSERT_EQ(loaded.colour.textures.size(), 1u);
  const Texture& t = loaded.colour.textures[0];
  EXPECT_EQ(t.name, "CesiumLogoFlat.png");
  EXPECT_EQ(t.mime_type, "image/png");
  EXPECT_EQ(t.bytes, box_png());
  // The PNG's IHDR holds its size (big-endian), read here without libpng.
  const auto be32 = [&](std::size_t at) {
    return int(std::uint8_t(t.bytes[at])) << 24 | int(std::uint8_t(t.bytes[at + 1])) << 16 |
           int(std::uint8_t(t.bytes[at + 2])) << 8 | int(std::uint8_t(t.bytes[at + 3]));
  };
  EXPECT_EQ(t.width, be32(16));
  EXPECT_EQ(t.height, be32(20));
  EXPECT_EQ(t.sampler.wrap_s, 10497);
  EXPECT_EQ(t.sampler.mag_filter, 9729);
  EXPECT_EQ(t.sampler.min_filter, 9986);
}

TEST(LoadColour, DuckHasATextureAndUvsOnEveryFace) {
  const LoadedMesh duck = load_mesh_file(papernet::test::test_data_dir() + "/Duck.glb");
  ASSERT_EQ(duck.colour.uvs.size(), duck.mesh.faces.size());
  for (const auto& f : duck.colour.uvs)
    for (const UV& uv : f) ASSERT_TRUE(std::isfinite(uv[0]) && std::isfinite(uv[1]));
  ASSERT_EQ(duck.colour.textures.size(), 1u);
  EXPECT_GT(duck.colour.textures[0].width, 0);
  EXPECT_EQ(duck.colour.materials.at(0).texture, 0);
}

using test::base64;

/// A unit square (2 triangles) with TEXCOORD_0 = position, a material sampling `image` (a data
/// URI, or a file name) through `texture_info`, all in one .gltf with a data-URI buffer.
json textured_square(const std::string& image_uri, json texture_info = json::object()) {
  const float p[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float uv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  const std::uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
  std::string buffer(reinterpret_cast<const char*>(p), 48);
  buffer.append(reinterpret_cast<const char*>(uv), 32);
  buffer.append(reinterpret_cast<const char*>(idx), 12);
  texture_info["index"] = 0;
  return {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}},
            {"indices", 2},
            {"material", 0}}}}}}},
      {"materials",
       {{{"name", "square"},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {1, 0.5, 0.25, 1}}, {"baseColorTexture", texture_info}}}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}}},
      {"samplers", {{{"wrapS", 33071}, {"wrapT", 33648}}}},
      {"images", {{{"uri", image_uri}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
        {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 12}}}},
      {"buffers",
       {{{"uri", "data:application/octet-stream;base64," + base64(buffer)}, {"byteLength", 92}}}}};
}

std::string png_uri(const std::string& png) { return "data:image/png;base64," + base64(png); }

bool has_note(const LoadedMesh& m, const std::string& part) {
  for (const std::string& n : m.notes)
    if (n.find(part) != std::string::npos) return true;
  return false;
}

TEST(LoadColour, DataUriImageSamplerAndFactor) {
  const LoadedMesh m = load_mesh(textured_square(png_uri(box_png())).dump(), MeshFormat::Gltf);
  ASSERT_EQ(m.colour.textures.size(), 1u);
  EXPECT_EQ(m.colour.textures[0].bytes, box_png());
  EXPECT_EQ(m.colour.textures[0].sampler.wrap_s, 33071);
  EXPECT_EQ(m.colour.textures[0].sampler.wrap_t, 33648);
  EXPECT_EQ(m.colour.materials[0].base_color, (RGBA{1, 0.5, 0.25, 1}));
  ASSERT_EQ(m.colour.uvs.size(), 2u);
  EXPECT_EQ(m.colour.uvs[0], (std::array<UV, 3>{UV{0, 0}, UV{1, 0}, UV{1, 1}}));
  EXPECT_EQ(m.colour.uvs[1], (std::array<UV, 3>{UV{0, 0}, UV{1, 1}, UV{0, 1}}));
}

TEST(LoadColour, KhrTextureTransformIsAppliedToTheUvs) {
  // offset (0.5, 0.25), rotation 90 degrees, scale (2, 3): u' = c*sx*u + s*sy*v + ox,
  // v' = -s*sx*u + c*sy*v + oy (the extension's matrix T * R * S).
  const json transform = {
      {"extensions",
       {{"KHR_texture_transform",
         {{"offset", {0.5, 0.25}}, {"rotation", std::numbers::pi / 2}, {"scale", {2, 3}}}}}}};
  const LoadedMesh m =
      load_mesh(textured_square(png_uri(box_png()), transform).dump(), MeshFormat::Gltf);
  ASSERT_EQ(m.colour.uvs.size(), 2u);
  const auto expect = [](double u, double v) { return UV{3 * v + 0.5, -2 * u + 0.25}; };
  const UV corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const int faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (int f = 0; f < 2; ++f)
    for (int k = 0; k < 3; ++k) {
      const UV want = expect(corners[faces[f][k]][0], corners[faces[f][k]][1]);
      EXPECT_NEAR(m.colour.uvs[f][k][0], want[0], 1e-12);
      EXPECT_NEAR(m.colour.uvs[f][k][1], want[1], 1e-12);
    }
}

TEST(LoadColour, AnImageThatCannotBeUsedLeavesTheMaterialUntexturedWithANote) {
  const std::string png = box_png();
  const std::string ktx2 = std::string("\xabKTX 20\xbb\r\n\x1a\n", 12) + std::string(64, '\0');
  const std::string webp = std::string("RIFF\x10\0\0\0WEBPVP8 ", 16) + std::string(32, '\0');
  const struct {
    std::string uri, note;
  } cases[] = {
      {png_uri(png.substr(0, png.size() / 2)), "cannot be used"},  // truncated
      {png_uri(png.substr(0, 30)), "cannot be used"},              // cut inside a chunk
      {png_uri(std::string(100, 'x')), "not a PNG or JPEG"},
      {"data:image/ktx2;base64," + base64(ktx2), "image/ktx2"},
      {"data:image/webp;base64," + base64(webp), "image/webp"},
      {"texture.png", "not supplied"},  // an external file not uploaded with the model
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.note);
    const LoadedMesh m = load_mesh(textured_square(c.uri).dump(), MeshFormat::Gltf);
    EXPECT_EQ(m.mesh.faces.size(), 2u);
    EXPECT_EQ(m.colour.uvs.size(), 2u);
    ASSERT_EQ(m.colour.materials.size(), 1u);
    EXPECT_EQ(m.colour.materials[0].texture, -1);
    EXPECT_TRUE(m.colour.textures.empty());
    EXPECT_TRUE(has_note(m, c.note)) << (m.notes.empty() ? "" : m.notes[0]);
  }
}

TEST(LoadColour, AnImageWhoseBufferViewLiesOutsideItsBufferIsLeftOutWithANote) {
  const Glb glb = split_glb(read_file(kBoxTextured));
  const int view = glb.doc["images"][0]["bufferView"].get<int>();
  const std::size_t size = glb.bin.size();
  // The view as the file has it loads the texture; one byte more, or a start past the buffer,
  // and the image is left out (tinygltf hands such a view over without checking it).
  const struct {
    std::size_t offset, length;
    bool inside;
  } cases[] = {
      {glb.doc["bufferViews"][view].value("byteOffset", std::size_t{0}),
       glb.doc["bufferViews"][view]["byteLength"].get<std::size_t>(), true},
      {glb.doc["bufferViews"][view].value("byteOffset", std::size_t{0}),
       size - glb.doc["bufferViews"][view].value("byteOffset", std::size_t{0}) + 1, false},
      {size + 4, 16, false},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(std::to_string(c.offset) + " + " + std::to_string(c.length) + " of " +
                 std::to_string(size));
    json doc = glb.doc;
    doc["bufferViews"][view]["byteOffset"] = c.offset;
    doc["bufferViews"][view]["byteLength"] = c.length;
    const LoadedMesh m = load_mesh(join_glb(doc, glb.bin), MeshFormat::Glb);
    EXPECT_EQ(m.mesh.faces.size(), 12u);
    EXPECT_EQ(m.colour.uvs.size(), 12u);
    ASSERT_EQ(m.colour.materials.size(), 1u);
    if (c.inside) {
      EXPECT_EQ(m.colour.materials[0].texture, 0);
      ASSERT_EQ(m.colour.textures.size(), 1u);
      EXPECT_EQ(m.colour.textures[0].bytes, box_png());
    } else {
      EXPECT_EQ(m.colour.materials[0].texture, -1);
      EXPECT_TRUE(m.colour.textures.empty());
      EXPECT_TRUE(has_note(m, "outside its buffer")) << (m.notes.empty() ? "" : m.notes[0]);
    }
  }
}

TEST(LoadColour, AnExternalImageSuppliedWithTheGltfIsUsed) {
  LoadOptions options;
  options.external_files["texture.png"] = box_png();
  const std::string text = textured_square("texture.png").dump();
  EXPECT_EQ(gltf_external_uris(text), std::vector<std::string>{"texture.png"});
  const LoadedMesh m = load_mesh(text, MeshFormat::Gltf, options);
  ASSERT_EQ(m.colour.textures.size(), 1u);
  EXPECT_EQ(m.colour.textures[0].bytes, box_png());
}

TEST(LoadColour, AnImageOverThePixelLimitIsRefused) {
  LoadOptions options;
  options.max_image_pixels = 100;
  try {
    load_mesh(textured_square(png_uri(box_png())).dump(), MeshFormat::Gltf, options);
    FAIL() << "no exception";
  } catch (const LimitExceededException& e) {
    EXPECT_EQ(e.limit(), LimitExceededException::Limit::Pixels);
    EXPECT_NE(std::string(e.what()).find("limit of 100 pixels"), std::string::npos);
  }
}

TEST(LoadColour, ImageDecoding) {
  const Image image = decode_image(box_png());
  EXPECT_GT(image.width, 0);
  EXPECT_EQ(image.rgba.size(), std::size_t(image.width) * std::size_t(image.height) * 4);
  const Image size = image_size(box_png());
  EXPECT_EQ(size.width, image.width);
  EXPECT_TRUE(size.rgba.empty());
  EXPECT_THROW(decode_image(box_png().substr(0, 200)), IOException);
  EXPECT_THROW(decode_image("\xff\xd8\xff\xe0 not really a jpeg"), IOException);
  EXPECT_THROW(decode_image(""), IOException);
}

TEST(LoadColour, JpegDecodingAndItsTruncation) {
  const std::string jpeg = read_file(papernet::test::test_data_dir() + "/gradient_16x8.jpg");
  ASSERT_EQ(sniff_image(jpeg), ImageFormat::Jpeg);
  const Image image = decode_image(jpeg);
  ASSERT_EQ(image.width, 16);
  ASSERT_EQ(image.height, 8);
  ASSERT_EQ(image.rgba.size(), 16u * 8 * 4);
  // The gradient it was written from, within JPEG's loss: red 16 x, green 32 y, blue 128.
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) {
      const std::uint8_t* p = &image.rgba[std::size_t(4 * (16 * y + x))];
      EXPECT_NEAR(p[0], 16 * x, 24);
      EXPECT_NEAR(p[1], 32 * y, 24);
      EXPECT_NEAR(p[2], 128, 24);
      EXPECT_EQ(p[3], 255);
    }
  EXPECT_THROW(decode_image(jpeg.substr(0, jpeg.size() - 40)), IOException);
  EXPECT_THROW(decode_image(jpeg.substr(0, 20)), IOException);
  EXPECT_THROW(decode_image(jpeg, 100), LimitExceededException);
}

// A square as an OBJ: vertex 2 repeated (a seam: same position, another texture coordinate),
// the second face wound the other way round from the first.
std::string seam_obj() {
  return "mtllib square.mtl\n"
         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 1 0\n"
         "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
         "usemtl logo\n"
         "f 1/1 2/2 3/3\n"
         "f 1/1 4/4 5/5\n";
}

TEST(LoadColour, ObjVtWithMtlIsReadWithVFlipped) {
  LoadOptions options;
  options.external_files["square.mtl"] =
      "newmtl logo\nKd 0.5 0.25 1\nd 0.75\nmap_Kd -s 1 1 1 logo.png\n";
  options.external_files["logo.png"] = box_png();
  const LoadedMesh m = load_mesh(seam_obj(), MeshFormat::Obj, options);
  ASSERT_EQ(m.colour.uvs.size(), 2u);
  EXPECT_EQ(m.colour.uvs[0], (std::array<UV, 3>{UV{0, 1}, UV{1, 1}, UV{1, 0}}));
  EXPECT_EQ(m.colour.uvs[1], (std::array<UV, 3>{UV{0, 1}, UV{0, 0}, UV{0.5, 0.5}}));
  ASSERT_EQ(m.colour.materials.size(), 1u);
  EXPECT_EQ(m.colour.materials[0].name, "logo");
  EXPECT_EQ(m.colour.materials[0].base_color, (RGBA{0.5, 0.25, 1, 0.75}));
  EXPECT_EQ(m.colour.materials[0].texture, 0);
  EXPECT_EQ(m.colour.face_materials, (std::vector<int>{0, 0}));
  EXPECT_EQ(m.colour.textures.at(0).bytes, box_png());
  // Without the image: the material stays, untextured, with a note.
  options.external_files.erase("logo.png");
  const LoadedMesh bare = load_mesh(seam_obj(), MeshFormat::Obj, options);
  EXPECT_EQ(bare.colour.materials.at(0).texture, -1);
  EXPECT_TRUE(has_note(bare, "logo.png"));
}

TEST(LoadColour, PlyVertexColoursPerCorner) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 51\n3 0 1 2\n";
  const LoadedMesh m = load_mesh(ply, MeshFormat::Ply);
  ASSERT_EQ(m.colour.colours.size(), 1u);
  EXPECT_EQ(m.colour.colours[0][0], (RGBA{1, 0, 0, 1}));
  EXPECT_EQ(m.colour.colours[0][1], (RGBA{0, 1, 0, 1}));
  EXPECT_EQ(m.colour.colours[0][2], (RGBA{0, 0, 0.2, 1}));
}

TEST(LoadColour, CornersKeepTheirUvsThroughWeldingAndRepair) {
  const LoadedMesh m = load_mesh(seam_obj(), MeshFormat::Obj);
  // Welding merged the repeated vertex; the two corners there keep their own coordinates.
  ASSERT_EQ(m.mesh.vertices.size(), 4u);
  EXPECT_EQ(m.mesh.faces[0][2], m.mesh.faces[1][2]);
  EXPECT_NE(m.colour.uvs[0][2], m.colour.uvs[1][2]);
  // Repair turns one face to agree with the other: its corners turn with it.
  const RepairResult repaired = repair_mesh(m.mesh, m.raw_faces);
  bool reoriented = false;
  for (const MeshRepair& r : repaired.repairs) reoriented |= r.code == "reoriented_faces";
  ASSERT_TRUE(reoriented);
  const MeshColour colour = remap_corners(m.colour, repaired.corners);
  ASSERT_EQ(colour.uvs.size(), repaired.mesh.faces.size());
  // Each output corner carries the UV its position had in its own input face.
  std::map<std::pair<std::size_t, std::array<double, 3>>, UV> uv_at;
  for (std::size_t f = 0; f < 2; ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = m.mesh.vertices[m.mesh.faces[f][k]];
      uv_at[{f, {p.x, p.y, p.z}}] = m.colour.uvs[f][k];
    }
  std::size_t flipped = 0;
  for (std::size_t f = 0; f < repaired.mesh.faces.size(); ++f) {
    const int origin = repaired.corners[f][0] / 3;
    flipped += repaired.corners[f][1] % 3 == 2;
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = repaired.mesh.vertices[repaired.mesh.faces[f][k]];
      EXPECT_EQ(repaired.corners[f][k] / 3, origin);
      EXPECT_EQ(colour.uvs[f][k], (uv_at[{std::size_t(origin), {p.x, p.y, p.z}}]))
          << "face " << f << " corner " << k;
    }
  }
  EXPECT_EQ(flipped, 1u);
  EXPECT_EQ(colour.face_materials, m.colour.face_materials);
}

}  // namespace
}  // namespace papernet
