// papernet-colour-bench [--model PATH] [--dpi N,N,...] [--detail auto|full]: what printing the
// model's colour costs (docs/colour.md "Printing", docs/performance.md). For each dpi the same
// job (200 mm on A4, layout fit, PDF and SVG pages) runs twice, each in a child process of its
// own so that its peak memory is its own: with colour none and with colour auto. Prints, per
// dpi, the colour pass's seconds per page (the difference of the two runs), both peaks, and the
// PDF and SVG bytes per page. Prints figures; it is not a test.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/child_process.h"
#include "core/io/load.h"
#include "engine/pipeline.h"

namespace papernet::bench {
namespace {

struct Run {
  double seconds = 0;
  int pages = 0;
  double pdf_bytes = 0, svg_bytes = 0;
  double peak_mb = 0;
};

// One job in this process: its seconds, pages and bytes (peak memory is the caller's).
Run run_once(const std::string& path, double dpi, bool colour, const std::string& detail) {
  JobInput input;
  input.mesh = read_mesh_file(path, std::size_t{256} << 20);
  input.format = format_from_extension(path);
  JobOptions options;
  options.dpi = dpi;
  options.colour = colour;
  options.size_mm = 200;
  options.layout = PageLayoutMode::Fit;
  if (detail == "full") options.detail = {DetailMode::Full, 0};
  PipelineProgress quiet;
  const auto start = std::chrono::steady_clock::now();
  const UnfoldOutcome out =
      run_pipeline(input, options, {}, {.svg_pages = true, .pdf = true}, quiet);
  Run r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.pages = out.print ? out.print->pages : 0;
  r.pdf_bytes = static_cast<double>(out.documents.pdf.size());
  for (const std::string& svg : out.documents.svg_pages) r.svg_bytes += svg.size();
  return r;
}

// run_once in a child process, with the child's peak resident memory.
Run in_child(const std::string& path, double dpi, bool colour, const std::string& detail) {
  const ChildRun child = bench::in_child([&] {
    const Run r = run_once(path, dpi, colour, detail);
    std::ostringstream o;
    o << r.seconds << ' ' << r.pages << ' ' << r.pdf_bytes << ' ' << r.svg_bytes;
    return o.str();
  });
  Run r;
  std::istringstream(child.text) >> r.seconds >> r.pages >> r.pdf_bytes >> r.svg_bytes;
  r.peak_mb = child.peak_mb;
  if (!child.ok || r.pages == 0)
    throw std::runtime_error("the run at " + std::to_string(dpi) + " dpi failed");
  return r;
}

std::vector<double> numbers(const std::string& list) {
  std::vector<double> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::stod(item));
  return out;
}

}  // namespace
}  // namespace papernet::bench

int main(int argc, char** argv) {
  using namespace papernet::bench;
  std::string model = std::string(PAPERNET_TEST_DATA) + "/Duck.glb", detail = "auto";
  std::vector<double> dpis{150, 300, 600};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--model")
      model = argv[i + 1];
    else if (flag == "--dpi")
      dpis = numbers(argv[i + 1]);
    else if (flag == "--detail")
      detail = argv[i + 1];
    else {
      std::cerr << "usage: papernet-colour-bench [--model PATH] [--dpi N,N,...] "
                   "[--detail auto|full]\n";
      return 1;
    }
  }
  try {
    std::printf("%s, 200 mm on A4, layout fit, detail %s: PDF and SVG pages\n\n", model.c_str(),
                detail.c_str());
    std::printf(
        "| dpi | pages | colour pass s/page | peak MB (line art) | peak MB (colour) | "
        "PDF MB/page | SVG MB/page |\n|---:|---:|---:|---:|---:|---:|---:|\n");
    for (double dpi : dpis) {
      const Run plain = in_child(model, dpi, false, detail);
      const Run colour = in_child(model, dpi, true, detail);
      const double pages = colour.pages;
      std::printf("| %.0f | %d | %.3f | %.0f | %.0f | %.2f | %.2f |\n", dpi, colour.pages,
                  (colour.seconds - plain.seconds) / pages, plain.peak_mb, colour.peak_mb,
                  colour.pdf_bytes / pages / 1e6, colour.svg_bytes / pages / 1e6);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::cerr << "papernet-colour-bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
