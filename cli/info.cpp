// `papernet info FILE [--json] [options]`: format, counts, genus, boundaries, every problem the
// file has, what repair makes of it and the pieces it becomes (engine/pipeline.h inspect_input).
// Exit 0 when it can be unfolded, 2 when it cannot (reason on stderr), 1 when the file is
// unreadable or unsupported, or an option is bad.
#include <exception>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/commands.h"
#include "cli/local_files.h"
#include "core/errors.h"
#include "core/io/json_text.h"
#include "engine/pipeline.h"

namespace papernet::cli {
namespace {

constexpr const char* kUsage =
    "usage: papernet info FILE [--json] [--strict] [--components all|largest]\n"
    "Describes a mesh (glb, gltf, drc, obj, off, ply, stl): counts, every problem the file has,\n"
    "what repair makes of it and how many pieces it unfolds into.\n"
    "  --json                 print a JSON object\n"
    "  --strict               judge the file as it is: what repair would fix is refused\n"
    "  --components largest   judge only the largest connected part\n"
    "Exit status: 0 unfoldable, 2 not unfoldable, 1 unreadable, unsupported or a bad option.\n";

}  // namespace

int info(int argc, char** argv) {
  std::string path;
  bool json = false;
  JobOptions options;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--help" || arg == "-h") {
        std::cout << kUsage;
        return 0;
      } else if (arg == "--json") {
        json = true;
      } else if (arg == "--strict") {
        options.strict = true;
      } else if (arg == "--components" && i + 1 < argc) {
        apply_option_flag(options, arg, argv[++i]);
      } else if (path.empty() && !arg.starts_with("-")) {
        path = arg;
      } else {
        throw std::invalid_argument("unknown option " + arg);
      }
    }
    if (path.empty()) throw std::invalid_argument("no file");
  } catch (const std::exception& e) {
    std::cerr << "papernet info: " << e.what() << "\n" << kUsage;
    return 1;
  }
  InputReport r;
  try {
    const PipelineLimits limits{std::size_t{256} << 20, 2'000'000, 60};
    r = inspect_input(read_local_input(path, limits.max_bytes), options, limits);
  } catch (const std::exception& e) {  // IOException; anything else is a bug, still reported
    if (json)
      std::cout << json_text(nlohmann::json{{"file", path}, {"error", e.what()}}, 2) << "\n";
    std::cerr << "papernet: " << path << ": " << e.what() << "\n";
    return 1;
  }
  const ValidationReport& v = r.as_loaded;
  if (json) {
    nlohmann::json problems = nlohmann::json::array(), repairs = nlohmann::json::array();
    for (const MeshProblem& p : v.problems)
      problems.push_back({{"code", p.code}, {"message", p.message}, {"blocking", p.blocking}});
    for (const NetRepair& p : r.repairs)
      repairs.push_back({{"code", p.code}, {"count", p.count}, {"message", p.message}});
    nlohmann::json out = {{"file", path},
                          {"format", format_name(r.format)},
                          {"vertices", v.vertices},
                          {"vertices_before_welding", r.raw_vertices},
                          {"faces", v.faces},
                          {"edges", v.edges},
                          {"components", v.components},
                          {"genus", v.genus},
                          {"boundaries", v.boundary_loops},
                          {"boundary_edges", v.boundary_edges},
                          {"problems", problems},
                          {"repairs", repairs},
                          {"pieces", r.pieces},
                          {"unfoldable", !r.refusal}};
    if (r.refusal) out["reason"] = *r.refusal;
    std::cout << json_text(out, 2) << "\n";
  } else {
    std::cout << "format:     " << format_name(r.format) << "\n"
              << "vertices:   " << v.vertices << " (" << r.raw_vertices << " before welding)\n"
              << "faces:      " << v.faces << "\n"
              << "components: " << v.components << "\n"
              << "genus:      " << v.genus << "\n"
              << "boundaries: " << v.boundary_loops << " (" << v.boundary_edges << " edges)\n";
    for (const MeshProblem& p : v.problems)
      std::cout << (p.blocking ? "problem:    " : "note:       ") << p.code << ": " << p.message
                << "\n";
    for (const NetRepair& p : r.repairs)
      std::cout << "repair:     " << p.code << ": " << p.message << "\n";
    if (!r.refusal) std::cout << "pieces:     " << r.pieces << "\n";
    std::cout << "unfoldable: " << (r.refusal ? "no" : "yes") << "\n";
  }
  if (r.refusal) {
    std::cerr << "papernet: " << path << ": cannot be unfolded: " << *r.refusal << "\n";
    return 2;
  }
  return 0;
}

}  // namespace papernet::cli
