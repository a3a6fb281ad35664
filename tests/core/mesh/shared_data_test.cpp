// Whole folders of ../shared/data/meshes: thingi-like (all unfoldable, counts against STATS.tsv
// and an independent boundary-loop walk), bad (each refused with a reason or loaded, in a child
// process with an address-space limit and a time limit), and gltf/draco (face counts against the
// files' own accessor counts). Each test skips with a message when the folder is absent.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/errors.h"
#include "core/io/load.h"
#include "core/mesh/validate.h"
#include "tests/support/files.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

namespace fs = std::filesystem;
const fs::path kMeshes = fs::path(papernet::test::shared_data_dir()) / "meshes";

using Row = std::map<std::string, std::string>;

/// STATS.tsv / SOURCES.tsv as file -> column -> value.
std::map<std::string, Row> read_tsv(const fs::path& path) {
  std::map<std::string, Row> rows;
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> header;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, '\t');) cells.push_back(cell);
    if (header.empty()) {
      header = cells;
      continue;
    }
    Row row;
    for (std::size_t i = 0; i < cells.size() && i < header.size(); ++i) row[header[i]] = cells[i];
    rows[cells.at(0)] = row;
  }
  return rows;
}

std::vector<fs::path> mesh_files(const fs::path& dir) {
  static const std::set<std::string> exts = {".obj", ".off",  ".ply", ".stl",
                                             ".glb", ".gltf", ".drc"};
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (e.is_regular_file() && exts.count(ext)) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

using test::read_file;

/// The files next to a .gltf that its buffers name, as an upload would bring them.
LoadOptions with_siblings(const fs::path& file) {
  LoadOptions o;
  if (format_from_extension(file.string()) != MeshFormat::Gltf) return o;
  for (const std::string& uri : gltf_external_uris(read_file(file)))
    if (fs::is_regular_file(file.parent_path() / uri))
      o.external_files[uri] = read_file(file.parent_path() / uri);
  return o;
}

/// Boundary loops counted by walking boundary half-edges (independent of validate's
/// union-find): each boundary edge used once, from its face's direction, to the next.
std::size_t walk_boundary_loops(const Mesh& m) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& f : m.faces)
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  std::multimap<int, int> next;  // boundary half-edge a -> b
  for (const auto& f : m.faces)
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      if (uses[{std::min(a, b), std::max(a, b)}] == 1) next.emplace(a, b);
    }
  std::size_t loops = 0;
  while (!next.empty()) {
    const int start = next.begin()->first;
    int v = start;
    do {
      const auto it = next.find(v);
      if (it == next.end()) break;
      v = it->second;
      next.erase(it);
    } while (v != start);
    ++loops;
  }
  return loops;
}

TEST(SharedData, EveryThingiLikeMeshLoadsIsUnfoldableAndMatchesStats) {
  const fs::path dir = kMeshes / "thingi-like";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "needs ../shared/data: " << dir << " is absent";
  const auto stats = read_tsv(kMeshes / "STATS.tsv");
  std::size_t checked = 0;
  for (const fs::path& file : mesh_files(dir)) {
    const std::string key = "thingi-like/" + file.filename().string();
    SCOPED_TRACE(key);
    const LoadedMesh loaded = load_mesh_file(file.string(), with_siblings(file));
    const ValidationReport r = validate(loaded);
    EXPECT_TRUE(r.unfoldable()) << r.reason();
    const auto it = stats.find(key);
    ASSERT_NE(it, stats.end()) << "not in STATS.tsv";
    const Row& s = it->second;
    EXPECT_EQ(r.vertices, std::stoul(s.at("V")));
    if (s.at("tris_only") == "1") {
      EXPECT_EQ(r.faces, std::stoul(s.at("F")));
    }
    EXPECT_EQ(r.components, std::stoul(s.at("components")));
    EXPECT_EQ(r.boundary_edges, std::stoul(s.at("boundary_edges")));
    EXPECT_EQ(long(r.vertices) - long(r.edges) + long(r.faces), std::stol(s.at("euler")));
    if (!s.at("genus").empty()) {
      EXPECT_EQ(r.genus, std::stol(s.at("genus")));
    }
    EXPECT_EQ(r.boundary_loops, walk_boundary_loops(loaded.mesh));
    // With one component: V - E + F = 2 - 2g - b.
    EXPECT_EQ(long(r.vertices) - long(r.edges) + long(r.faces),
              2 - 2 * r.genus - long(r.boundary_loops));
    ++checked;
  }
  EXPECT_GE(checked, 50u);
  std::cout << "thingi-like: " << checked << " meshes loaded, all unfoldable\n";
}

/// Loads and validates one file in a child process limited to `limit` bytes of address space
/// above what it already uses and 30 s, so that a crash, hang or huge allocation fails the test
/// instead of the test run. Returns "<status>\t<message>"; raises `max_rss_kb` to the child's
/// peak resident set.
std::string judge_in_child(const fs::path& file, std::size_t limit, long& max_rss_kb) {
  int fds[2];
  if (pipe(fds) != 0) return "pipe failed";
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    std::ifstream statm("/proc/self/statm");
    std::size_t pages = 0;
    statm >> pages;
    const rlim_t cap = rlim_t(pages) * sysconf(_SC_PAGESIZE) + limit;
    const rlimit rl{cap, cap};
    setrlimit(RLIMIT_AS, &rl);
    alarm(30);
    std::string out;
    try {
      const LoadedMesh m = load_mesh_file(file.string(), with_siblings(file));
      const ValidationReport r = validate(m);
      out = r.unfoldable() ? "loaded\t" + std::to_string(r.faces) + " faces"
                           : "invalid\t" + r.reason();
    } catch (const IOException& e) {
      out = std::string("refused\t") + e.what();
    } catch (const std::bad_alloc&) {
      out = "ALLOCATION FAILED\tover the address-space limit";
    } catch (const std::exception& e) {
      out = std::string("OTHER EXCEPTION\t") + e.what();
    }
    [[maybe_unused]] auto n = write(fds[1], out.data(), out.size());
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  std::string out;
  char buf[4096];
  for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;) out.append(buf, std::size_t(n));
  close(fds[0]);
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  max_rss_kb = std::max(max_rss_kb, usage.ru_maxrss);
  if (WIFSIGNALED(status)) return "CRASHED\tsignal " + std::to_string(WTERMSIG(status));
  return out;
}

TEST(SharedData, EveryBadFileIsRefusedWithAReasonOrLoadsWithinBounds) {
  const fs::path dir = kMeshes / "bad";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "needs ../shared/data: " << dir << " is absent";
  std::map<std::string, int> tally;
  long max_rss_kb = 0;
  for (const fs::path& file : mesh_files(dir)) {
    const std::string name = fs::relative(file, dir).string();
    const std::string result = judge_in_child(file, std::size_t{384} << 20, max_rss_kb);
    const std::string status = result.substr(0, result.find('\t'));
    const std::string message = result.substr(result.find('\t') + 1);
    EXPECT_TRUE(status == "loaded" || status == "invalid" || status == "refused")
        << name << ": " << result;
    EXPECT_FALSE(message.empty()) << name;
    ++tally[status];
    std::cout << "bad/" << name << ": " << status << ": " << message << "\n";
  }
  EXPECT_GT(tally["invalid"] + tally["refused"], tally["loaded"]);
  for (const auto& [status, n] : tally) std::cout << "bad: " << n << " " << status << "\n";
  std::cout << "bad: largest resident set of a child: " << max_rss_kb / 1024 << " MB\n";
}

/// Faces the glTF itself declares for its default scene: per instanced triangle primitive, its
/// index (or position) accessor count / 3 - read from the JSON, not through the loader.
std::size_t declared_gltf_faces(const std::string& bytes) {
  std::string text = bytes;
  if (bytes.substr(0, 4) == "glTF") {
    std::uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    text = bytes.substr(20, length);
  }
  const auto doc = nlohmann::json::parse(text);
  std::size_t faces = 0;
  auto mesh_faces = [&](int mesh) {
    for (const auto& prim : doc["meshes"][mesh]["primitives"]) {
      if (prim.value("mode", 4) != 4) continue;
      const int acc = prim.contains("indices") ? prim["indices"].get<int>()
                                               : prim["attributes"]["POSITION"].get<int>();
      faces += doc["accessors"][acc]["count"].get<std::size_t>() / 3;
    }
  };
  std::function<void(int)> node = [&](int n) {
    const auto& nd = doc["nodes"][n];
    if (nd.contains("mesh")) mesh_faces(nd["mesh"]);
    for (int c : nd.value("children", std::vector<int>{})) node(c);
  };
  if (doc.contains("scenes") && !doc["scenes"].empty()) {
    const int scene = doc.value("scene", 0);
    for (int n : doc["scenes"][scene].value("nodes", std::vector<int>{})) node(n);
  } else {
    for (std::size_t m = 0; m < doc["meshes"].size(); ++m) mesh_faces(int(m));
  }
  return faces;
}

TEST(SharedData, GltfAndDracoFilesLoadWithTheirDeclaredFaceCounts) {
  if (!fs::is_directory(kMeshes / "gltf") || !fs::is_directory(kMeshes / "draco"))
    GTEST_SKIP() << "needs ../shared/data: meshes/gltf and meshes/draco are absent";
  const auto sources = read_tsv(kMeshes / "SOURCES.tsv");
  std::size_t loaded = 0, refused = 0;
  for (const char* folder : {"gltf", "draco"})
    for (const fs::path& file : mesh_files(kMeshes / folder)) {
      const std::string key = fs::relative(file, kMeshes).string();
      SCOPED_TRACE(key);
      LoadedMesh m;
      try {
        m = load_mesh_file(file.string(), with_siblings(file));
      } catch (const IOException& e) {
        ++refused;
        std::cout << key << ": refused: " << e.what() << "\n";
        EXPECT_GT(std::string(e.what()).size(), 10u);
        continue;
      }
      ++loaded;
      std::size_t expected = 0;
      if (m.format == MeshFormat::Draco)
        expected = std::stoul(sources.at(key).at("faces"));  // counted by draco_decoder
      else
        expected = declared_gltf_faces(read_file(file));
      EXPECT_EQ(m.mesh.faces.size(), expected);
      EXPECT_LE(m.mesh.vertices.size(), m.raw_vertices);
    }
  std::cout << "gltf+draco: " << loaded << " loaded, " << refused << " refused\n";
  EXPECT_GT(loaded, 30u);
}

}  // namespace
}  // namespace papernet
