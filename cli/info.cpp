// `papernet info FILE [--json] [--keep-largest-component]`: format, counts, genus, boundaries and
// every problem. Exit 0 when the mesh can be unfolded, 2 when it cannot (reason on stderr), 1 when
// the file is unreadable or unsupported.
#include <exception>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/commands.h"
#include "cli/local_files.h"
#include "core/errors.h"
#include "core/io/load.h"
#include "core/mesh/validate.h"

namespace papernet::cli {

int info(int argc, char** argv) {
  std::string path;
  bool json = false;
  ValidateOptions vopt;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--json")
      json = true;
    else if (arg == "--keep-largest-component")
      vopt.keep_largest_component = true;
    else if (arg == "--help" || arg == "-h") {
      std::cout
          << "usage: papernet info FILE [--json] [--keep-largest-component]\n"
             "Describes a mesh (glb, gltf, drc, obj, off, ply, stl) and every problem in it.\n"
             "  --json                    print a JSON object\n"
             "  --keep-largest-component  judge only the largest connected component\n"
             "Exit status: 0 unfoldable, 2 not unfoldable, 1 unreadable or unsupported.\n";
      return 0;
    } else if (path.empty() && !arg.starts_with("--"))
      path = arg;
    else {
      std::cerr << "usage: papernet info FILE [--json] [--keep-largest-component]\n";
      return 1;
    }
  }
  if (path.empty()) {
    std::cerr << "usage: papernet info FILE [--json] [--keep-largest-component]\n";
    return 1;
  }
  LoadedMesh loaded;
  try {
    LoadOptions lopt;
    const JobInput input = read_local_input(path, lopt.max_bytes);
    lopt.external_files = input.external_files;
    loaded = load_mesh(input.mesh, input.format, lopt);
  } catch (const std::exception& e) {  // IOException; anything else is a bug, still reported
    if (json) std::cout << nlohmann::json{{"file", path}, {"error", e.what()}}.dump(2) << "\n";
    std::cerr << "papernet: " << path << ": " << e.what() << "\n";
    return 1;
  }
  const ValidationReport r = validate(loaded, vopt);
  if (json) {
    nlohmann::json problems = nlohmann::json::array();
    for (const MeshProblem& p : r.problems)
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
    for (const MeshProblem& p : r.problems)
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
