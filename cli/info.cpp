// `papernet info FILE [--json] [--largest]`: format, counts, genus, boundaries and every problem.
// Exit 0 when the mesh can be unfolded, 2 when it cannot (reason on stderr), 1 when the file is
// unreadable or unsupported.
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/commands.h"
#include "core/errors.h"
#include "core/io/load.h"
#include "core/mesh/validate.h"

namespace papernet::cli {
namespace {

/// A buffer name a .gltf may use to reach a sibling file: relative, inside the folder.
bool safe_relative_name(const std::string& uri) {
  if (uri.empty() || uri.find("://") != std::string::npos || uri.find(':') != std::string::npos ||
      uri.front() == '/' || uri.find('\\') != std::string::npos)
    return false;
  for (const auto& part : std::filesystem::path(uri))
    if (part == "..") return false;
  return true;
}

/// Reads the sibling files a .gltf's buffers name, so that they come "with the upload".
void add_gltf_siblings(const std::string& path, LoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::string> uris;
  try {
    uris = gltf_external_uris(text);
  } catch (const IOException&) {
    return;  // the loader says what is wrong with the file
  }
  const auto dir = std::filesystem::path(path).parent_path();
  for (const std::string& uri : uris) {
    if (!safe_relative_name(uri)) continue;  // never supplied: loading names it as missing
    const auto sibling = dir / uri;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(sibling, ec)) continue;
    if (std::filesystem::file_size(sibling, ec) > options.max_bytes) continue;
    std::ifstream s(sibling, std::ios::binary);
    options.external_files[uri].assign(std::istreambuf_iterator<char>(s),
                                       std::istreambuf_iterator<char>());
  }
}

}  // namespace

int info(int argc, char** argv) {
  std::string path;
  bool json = false;
  ValidateOptions vopt;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--json")
      json = true;
    else if (arg == "--largest")
      vopt.keep_largest_component = true;
    else if (arg == "--help" || arg == "-h") {
      std::cout
          << "usage: papernet info FILE [--json] [--largest]\n"
             "Describes a mesh (glb, gltf, drc, obj, off, ply, stl) and every problem in it.\n"
             "  --json     print a JSON object\n"
             "  --largest  judge only the largest connected component\n"
             "Exit status: 0 unfoldable, 2 not unfoldable, 1 unreadable or unsupported.\n";
      return 0;
    } else if (path.empty() && !arg.starts_with("--"))
      path = arg;
    else {
      std::cerr << "usage: papernet info FILE [--json] [--largest]\n";
      return 1;
    }
  }
  if (path.empty()) {
    std::cerr << "usage: papernet info FILE [--json] [--largest]\n";
    return 1;
  }
  LoadOptions lopt;
  if (format_from_extension(path) == MeshFormat::Gltf) add_gltf_siblings(path, lopt);
  LoadedMesh loaded;
  try {
    loaded = load_mesh_file(path, lopt);
  } catch (const std::exception& e) {  // IOException; anything else is a bug, still reported
    if (json) std::cout << nlohmann::json{{"file", path}, {"error", e.what()}}.dump(2) << "\n";
    std::cerr << "papernet: " << path << ": " << e.what() << "\n";
    return 1;
  }
  const ValidationReport r = validate(loaded, vopt);
  if (json) {
    nlohmann::json problems = nlohmann::json::array();
    for (const Problem& p : r.problems)
      problems.push_back({{"code", p.code}, {"message", p.message}, {"blocking", p.blocking}});
    nlohmann::json out = {{"file", path},
                          {"format", format_name(loaded.format)},
                          {"vertices", r.vertices},
                          {"vertices_before_welding", loaded.raw_vertices},
                          {"faces", r.faces},
                          {"edges", r.edges},
                          {"components", r.components},
                          {"genus", r.genus},
                          {"boundaries", r.boundary_loops},
                          {"boundary_edges", r.boundary_edges},
                          {"unfoldable", r.unfoldable()},
                          {"problems", problems},
                          {"notes", loaded.notes}};
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << "format:     " << format_name(loaded.format) << "\n"
              << "vertices:   " << r.vertices << " (" << loaded.raw_vertices << " before welding)\n"
              << "faces:      " << r.faces << "\n"
              << "components: " << r.components << "\n"
              << "genus:      " << r.genus << "\n"
              << "boundaries: " << r.boundary_loops << " (" << r.boundary_edges << " edges)\n";
    for (const std::string& note : loaded.notes) std::cout << "note:       " << note << "\n";
    for (const Problem& p : r.problems)
      std::cout << (p.blocking ? "problem:    " : "note:       ") << p.code << ": " << p.message
                << "\n";
    std::cout << "unfoldable: " << (r.unfoldable() ? "yes" : "no") << "\n";
  }
  if (!r.unfoldable()) {
    std::cerr << "papernet: " << path << ": cannot be unfolded: " << r.reason() << "\n";
    return 2;
  }
  return 0;
}

}  // namespace papernet::cli
