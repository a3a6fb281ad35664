// papernet-scale-bench [--meshes PATH,PATH,...] [--strategies AUTO,TU] [--time-limit S]
// How far unfolding goes on large meshes with every face kept (docs/performance.md, "Scale"):
// each mesh with each strategy as one job in a child process of its own (detail full, the net
// JSON only, the time limit of the command line), and its result (complete or approximate), the
// faces of the net it returns, seconds until the net and for the whole job (with the pass that
// makes room for glue tabs, which has what the unfold leaves of the limit), and peak memory. By
// default the 20,000- and 100,000-face meshes of ../shared/data/meshes/classic and two between.
// Prints figures; it is not a test.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/child_process.h"
#include "core/io/load.h"
#include "engine/pipeline.h"

namespace papernet::bench {
namespace {

struct Result {
  std::string result;  ///< "complete", "approximate", or the error
  std::size_t input_faces = 0, faces = 0;
  double unfold_seconds = 0;  ///< until the net (load, repair, unfold)
  double seconds = 0;         ///< the whole job, with the pass that makes room for glue tabs
};

Result run_once(const std::string& path, Strategy strategy, double time_limit) {
  JobInput input;
  input.mesh = read_mesh_file(path, std::size_t{256} << 20);
  input.format = format_from_extension(path);
  JobOptions options;
  options.strategy = strategy;
  options.detail = {DetailMode::Full, 0};
  options.time_limit = time_limit;
  PipelineLimits limits;
  limits.max_bytes = std::size_t{256} << 20;
  PipelineProgress quiet;
  const auto start = std::chrono::steady_clock::now();
  const UnfoldOutcome out = run_pipeline(input, options, limits, {}, quiet);
  Result r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.result = out.net.result;
  r.input_faces = out.net.input.faces;
  r.faces = out.net.mesh.faces.size();
  r.unfold_seconds = out.net.metrics.seconds;
  return r;
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

Strategy strategy_named(const std::string& name) {
  for (Strategy s : {Strategy::AUTO, Strategy::QQ, Strategy::SEMP, Strategy::SEQ, Strategy::TU})
    if (strategy_name(s) == name) return s;
  throw std::runtime_error("unknown strategy " + name);
}

}  // namespace
}  // namespace papernet::bench

int main(int argc, char** argv) {
  using namespace papernet;
  using namespace papernet::bench;
  const std::string classic = PAPERNET_SHARED_DATA "/meshes/classic/";
  std::vector<std::string> meshes{classic + "c3d__rocker-arm.obj", classic + "c3d__beetle-alt.obj",
                                  classic + "c3d__beast.obj", classic + "c3d__nefertiti.obj"};
  std::vector<std::string> strategies{"AUTO", "TU"};
  double time_limit = 60;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--meshes")
      meshes = split(value);
    else if (flag == "--strategies")
      strategies = split(value);
    else if (flag == "--time-limit")
      time_limit = std::stod(value);
    else {
      std::cerr << "usage: papernet-scale-bench [--meshes PATH,...] [--strategies AUTO,TU] "
                   "[--time-limit S]\n";
      return 1;
    }
  }
  if (argc % 2 == 0) {
    std::cerr << "papernet-scale-bench: " << argv[argc - 1] << " needs a value\n";
    return 1;
  }
  try {
    std::printf("detail full, %.0f s limit, each run in a child process of its own\n\n",
                time_limit);
    std::printf(
        "| mesh | faces | strategy | result | faces of the net | unfold s | job s | peak MB |\n");
    std::printf("|---|---:|---|---|---:|---:|---:|---:|\n");
    for (const std::string& path : meshes) {
      if (!std::filesystem::exists(path)) throw std::runtime_error("no " + path);
      for (const std::string& name : strategies) {
        const Strategy strategy = strategy_named(name);
        const ChildRun child = in_child([&] {
          const Result r = run_once(path, strategy, time_limit);
          std::ostringstream o;
          o << r.result << ' ' << r.input_faces << ' ' << r.faces << ' ' << r.unfold_seconds << ' '
            << r.seconds;
          return o.str();
        });
        Result r;
        std::istringstream(child.text) >> r.result >> r.input_faces >> r.faces >>
            r.unfold_seconds >> r.seconds;
        if (!child.ok) r.result = "failed";
        std::printf("| %s | %zu | %s | %s | %zu | %.1f | %.1f | %.0f |\n",
                    std::filesystem::path(path).stem().string().c_str(), r.input_faces,
                    name.c_str(), r.result.c_str(), r.faces, r.unfold_seconds, r.seconds,
                    child.peak_mb);
        std::fflush(stdout);
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "papernet-scale-bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
