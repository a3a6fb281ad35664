#include "server/upload.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <tuple>
#include <vector>

#include "server/problem.h"
#include "tests/support/paths.h"

using namespace papernet;
using namespace papernet::server;

namespace {

std::string read(const std::string& name) {
  std::ifstream in(papernet::test::test_data_dir() + "/" + name, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string problem_code(const UploadRequest& request) {
  try {
    parse_upload(request, {});
  } catch (const ApiError& e) {
    return e.problem().code;
  } catch (const InvalidOptionException& e) {
    return e.code();
  }
  return "";
}

}  // namespace

TEST(UploadTest, UndeclaredFormatIsSniffed) {
  for (const auto& [file, format] :
       std::vector<std::pair<std::string, MeshFormat>>{{"sample.obj", MeshFormat::Obj},
                                                       {"Duck.glb", MeshFormat::Glb},
                                                       {"mirror.ply", MeshFormat::Ply},
                                                       {"thingi10k_65004.stl", MeshFormat::Stl}}) {
    UploadRequest r;
    r.content_type = "application/octet-stream";
    r.body = read(file);
    EXPECT_EQ(parse_upload(r, {}).input.format, format) << file;
  }
}

TEST(UploadTest, DeclaredFormatWinsOverContent) {
  UploadRequest r;
  r.content_type = "model/stl";
  r.body = read("sample.obj");
  EXPECT_EQ(parse_upload(r, {}).input.format, MeshFormat::Stl);
  r.query = {{"format", "off"}};
  EXPECT_EQ(parse_upload(r, {}).input.format, MeshFormat::Off);
}

// Bytes whose signature names another format than the one declared answer 415 naming both;
// formats told only by a guess (OBJ, ASCII STL) contradict nothing.
TEST(UploadTest, BytesThatContradictTheDeclaredFormatAre415NamingBoth) {
  for (const auto& [file, type, sniffed] :
       std::vector<std::tuple<std::string, std::string, std::string>>{
           {"Duck.glb", "model/obj", "glb"},
           {"mirror.ply", "model/stl", "ply"},
           {"thingi10k_65004.stl", "model/x-ply", "stl"},
           {"gltf_external/Box.gltf", "model/gltf-binary", "gltf"}}) {
    UploadRequest r;
    r.content_type = type;
    r.body = read(file);
    try {
      parse_upload(r, {});
      ADD_FAILURE() << file << " was accepted as " << type;
    } catch (const ApiError& e) {
      EXPECT_EQ(e.problem().status, 415) << file;
      EXPECT_NE(e.problem().detail.find("is " + sniffed + " by its content"), std::string::npos)
          << e.problem().detail;
      EXPECT_NE(e.problem().detail.find(type), std::string::npos) << e.problem().detail;
    }
  }
  UploadRequest multipart;  // the declared type of a multipart's mesh part too
  multipart.multipart = true;
  multipart.parts = {{"mesh", "duck.obj", "model/obj", read("Duck.glb")}};
  EXPECT_EQ(problem_code(multipart), "unsupported_format");
}

TEST(UploadTest, ContentThatIsNoMeshIsUnsupported) {
  UploadRequest png;
  png.content_type = "application/octet-stream";
  png.body = std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
  EXPECT_EQ(problem_code(png), "unsupported_format");
}

TEST(UploadTest, MediaTypes) {
  EXPECT_EQ(format_from_media_type("model/gltf-binary"), MeshFormat::Glb);
  EXPECT_EQ(format_from_media_type("model/gltf+json; charset=utf-8"), MeshFormat::Gltf);
  EXPECT_EQ(format_from_media_type("model/stl"), MeshFormat::Stl);
  EXPECT_EQ(format_from_media_type("application/octet-stream"), MeshFormat::Unknown);
  EXPECT_EQ(format_from_media_type(""), MeshFormat::Unknown);
  EXPECT_THROW(format_from_media_type("image/png"), ApiError);
}

TEST(UploadTest, RawBodyWithQueryOptions) {
  UploadRequest r;
  r.content_type = "application/octet-stream";
  r.body = read("Duck.glb");
  r.query = {{"strategy", "SEQ"}, {"seed", "5"}};
  const ParsedUpload up = parse_upload(r, {});
  EXPECT_EQ(up.input.format, MeshFormat::Glb);
  EXPECT_EQ(up.input.mesh.size(), r.body.size());
  EXPECT_EQ(up.options.strategy, Strategy::SEQ);
  EXPECT_EQ(up.options.seed, 5u);
}

TEST(UploadTest, MultipartWithBuffersAndOptions) {
  UploadRequest r;
  r.multipart = true;
  r.parts = {{"mesh", "box.gltf", "application/octet-stream", R"({"asset":{"version":"2.0"}})"},
             {"buffers", "box.bin", "application/octet-stream", "0123"},
             {"options", "", "application/json", R"({"strategy":"TU"})"}};
  const ParsedUpload up = parse_upload(r, {});
  EXPECT_EQ(up.input.format, MeshFormat::Gltf);
  ASSERT_EQ(up.input.external_files.count("box.bin"), 1u);
  EXPECT_EQ(up.input.external_files.at("box.bin"), "0123");
  EXPECT_EQ(up.options.strategy, Strategy::TU);
}

TEST(UploadTest, RequestFaultsHaveCodes) {
  UploadRequest empty;
  EXPECT_EQ(problem_code(empty), "missing_mesh");

  UploadRequest png;
  png.content_type = "image/png";
  png.body = "x";
  EXPECT_EQ(problem_code(png), "unsupported_format");

  UploadRequest unknown;
  unknown.body = "just some words\nand more\n";
  EXPECT_EQ(problem_code(unknown), "unsupported_format");

  UploadRequest bad_format;
  bad_format.body = read("sample.obj");
  bad_format.query = {{"format", "dwg"}};
  EXPECT_EQ(problem_code(bad_format), "unsupported_format");

  UploadRequest no_mesh_part;
  no_mesh_part.multipart = true;
  no_mesh_part.parts = {{"options", "", "application/json", "{}"}};
  EXPECT_EQ(problem_code(no_mesh_part), "missing_mesh");

  UploadRequest traversal;
  traversal.multipart = true;
  traversal.parts = {{"mesh", "a.gltf", "", "{}"}, {"buffers", "../../etc/passwd", "", "x"}};
  EXPECT_EQ(problem_code(traversal), "malformed_request");

  UploadRequest both;
  both.multipart = true;
  both.parts = {{"mesh", "a.obj", "", read("sample.obj")}, {"options", "", "", "{}"}};
  both.query = {{"seed", "3"}};
  EXPECT_EQ(problem_code(both), "conflicting_options");

  UploadRequest bad_option;
  bad_option.body = read("sample.obj");
  bad_option.query = {{"strategy", "XX"}};
  EXPECT_EQ(problem_code(bad_option), "invalid_option_value");
}
