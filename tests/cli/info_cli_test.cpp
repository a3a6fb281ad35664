// `papernet info` as a user runs it: exit codes, the JSON it prints, and a .gltf whose buffers
// are read from next to it only when named by a safe relative path.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/support/paths.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string out;
};

CliRun info(const std::string& args) {
  CliRun r;
  FILE* p =
      popen((papernet::test::papernet_binary() + " info " + args + " 2>/dev/null").c_str(), "r");
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) r.out.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

const std::string kData = papernet::test::test_data_dir();

TEST(InfoCli, UnfoldableMeshExitsZeroWithItsCounts) {
  const CliRun r = info(kData + "/thingi10k_65004.stl --json");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["format"], "stl");
  EXPECT_EQ(j["faces"], 1466);
  EXPECT_EQ(j["genus"], 2);
  EXPECT_EQ(j["boundaries"], 0);
  EXPECT_EQ(j["unfoldable"], true);
}

TEST(InfoCli, UnreadableFileExitsOneAndUnfoldableNotExitsTwo) {
  EXPECT_EQ(info(kData + "/LICENSES.md").code, 1);
  EXPECT_EQ(info(kData + "/does_not_exist.obj").code, 1);
  const papernet::test::ScratchDir scratch("papernet_info_cli");
  const fs::path& dir = scratch.path();
  std::ofstream(dir / "two.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 0\nv 6 0 0\nv 5 1 0\n"
                                    "f 1 2 3\nf 4 5 6\n";
  // The error quotes the file's bad token; a byte that is not UTF-8 is quoted as U+FFFD (the
  // JSON could not be written before: the program aborted).
  std::ofstream(dir / "bad.obj", std::ios::binary) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \xC5x\n";
  CliRun bad = info((dir / "bad.obj").string() + " --json");
  EXPECT_EQ(bad.code, 1);
  EXPECT_EQ(nlohmann::json::parse(bad.out)["error"], "obj line 4: bad face index '\xEF\xBF\xBDx'")
      << bad.out;
  // Two parts: two pieces, unless --strict refuses a mesh in parts (or judges the largest).
  CliRun r = info((dir / "two.obj").string() + " --json");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(nlohmann::json::parse(r.out)["problems"][0]["code"], "several_components");
  EXPECT_EQ(nlohmann::json::parse(r.out)["pieces"], 2);
  r = info((dir / "two.obj").string() + " --json --strict");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(nlohmann::json::parse(r.out)["unfoldable"], false);
  EXPECT_EQ(info((dir / "two.obj").string() + " --strict --components largest").code, 0);
  // Nothing to unfold, repair or not: exit 2.
  std::ofstream(dir / "points.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_EQ(info((dir / "points.obj").string()).code, 2);
  // A pinch repaired: reported, unfoldable; refused with --strict.
  std::ofstream(dir / "pinch.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv -1 0 0\nv 0 -1 0\n"
                                      "v 0 0 -1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 1 5 6\n"
                                      "f 1 6 7\nf 5 7 6\nf 1 7 5\n";
  r = info((dir / "pinch.obj").string() + " --json");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(nlohmann::json::parse(r.out)["repairs"][0]["code"], "split_pinched_vertices");
  EXPECT_EQ(info((dir / "pinch.obj").string() + " --strict").code, 2);
}

TEST(InfoCli, GltfReadsSiblingBuffersButNeverParentPaths) {
  const papernet::test::ScratchDir scratch("papernet_info_cli");
  const fs::path dir = scratch.path() / "model";
  fs::create_directories(dir);
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::string bin(reinterpret_cast<const char*>(p), sizeof p);
  std::ofstream(dir / "tri.bin", std::ios::binary) << bin;
  std::ofstream(dir.parent_path() / "secret.bin", std::ios::binary) << bin;
  auto gltf = [](const std::string& uri) {
    nlohmann::json g = {
        {"asset", {{"version", "2.0"}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteLength", 36}}}},
        {"buffers", {{{"uri", uri}, {"byteLength", 36}}}}};
    return g.dump();
  };
  std::ofstream(dir / "ok.gltf") << gltf("tri.bin");
  std::ofstream(dir / "escape.gltf") << gltf("../secret.bin");
  EXPECT_EQ(info((dir / "ok.gltf").string()).code, 0);
  EXPECT_EQ(info((dir / "escape.gltf").string()).code, 1);
}

}  // namespace
