// papernet-print-bench [--bench DIR] [--res 400,1000] [--size-mm 200] [--detail full|auto|N]
//                      [--margin-mm 10] [--prefer sheets|pieces] [--blender TSV]
// What a person printing on A4 gets (docs/print.md, "Against Blender's exporter"): for each mesh
// of DIR/RES/*.obj, one job in this process as `papernet unfold MESH -o kit.pdf` runs it (layout
// fit, the default strategy, tabs auto, no colour) at SIZE mm with the given detail and page
// margins (papernet's default: 10 mm; the Blender run must use the same), saving sheets (the
// default) or pieces first (the job's `prefer`); the sheets,
// pieces, tabs, strips, smallest label and seconds. With --blender, the TSV that
// blender_print_peer.py wrote for the same meshes (Blender's bundled "Export Paper Model" add-on,
// "limit island size" on), side by side, and the targets counted. Prints Markdown; it is
// not a test.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/load.h"
#include "engine/pipeline.h"

namespace papernet::bench {
namespace {

namespace fs = std::filesystem;

struct Ours {
  std::string mesh;
  std::size_t faces = 0;
  int sheets = 0;  ///< pages without the overview: the sheets a person cuts
  bool overview = false;
  int pieces = 0;
  bool tiled = false;
  std::size_t tabs = 0, strips = 0, labels = 0, small_labels = 0;
  double smallest_label_mm = 0;  ///< 0 without labels
  double seconds = 0;
  std::string error;  ///< the job's error (refused), or empty
};

struct Peer {
  int islands = -1, pages = -1;
  double seconds = -1;
  std::string error;
};

Ours run_one(const fs::path& path, double size_mm, double margin_mm, const Detail& detail,
             FitGoal prefer) {
  Ours r;
  r.mesh = path.filename().string();
  const auto start = std::chrono::steady_clock::now();
  try {
    JobInput input;
    input.mesh = read_mesh_file(path.string(), std::size_t{256} << 20);
    input.format = format_from_extension(path.string());
    JobOptions options;
    options.size_mm = size_mm;
    options.margin_mm = margin_mm;
    options.layout = PageLayoutMode::Fit;
    options.colour = false;
    options.detail = detail;
    options.prefer = prefer;
    PipelineProgress quiet;
    const UnfoldOutcome out = run_pipeline(input, options, {}, {.pdf = true}, quiet);
    r.faces = out.net.mesh.faces.size();
    if (out.print) {
      r.overview = out.print->overview;
      r.sheets = out.print->pages - out.print->overview_pages;
      r.pieces = out.print->pieces;
      r.tiled = out.print->layout != "fit";
      r.tabs = out.print->tabs;
      r.strips = out.print->strips;
      r.labels = out.print->labels;
      r.small_labels = out.print->small_labels;
      r.smallest_label_mm = out.print->smallest_label_mm;
    }
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// blender_print_peer.py's TSV: res, mesh, faces, islands, pages, export_s, error.
std::map<std::string, Peer> read_peer(const std::string& path) {
  std::map<std::string, Peer> out;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, '\t');) f.push_back(cell);
    if (f.size() < 6) continue;
    Peer p;
    p.islands = std::stoi(f[3]);
    p.pages = std::stoi(f[4]);
    p.seconds = std::stod(f[5]);
    if (f.size() > 6) p.error = f[6];
    out[f[0] + "/" + f[1]] = p;
  }
  return out;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string short_error(std::string e) {
  std::replace(e.begin(), e.end(), '|', '/');
  return e.size() > 60 ? e.substr(0, 57) + "..." : e;
}

Detail parse_detail(const std::string& s) {
  if (s == "full") return {DetailMode::Full, 0};
  if (s == "auto") return {DetailMode::Auto, 0};
  return {DetailMode::Faces, static_cast<std::size_t>(std::stoul(s))};
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

int run(const std::string& bench, const std::vector<std::string>& resolutions, double size_mm,
        double margin_mm, const std::string& detail, FitGoal prefer, const std::string& blender) {
  const std::map<std::string, Peer> peer =
      blender.empty() ? std::map<std::string, Peer>{} : read_peer(blender);
  const bool with_peer = !peer.empty();
  for (const std::string& res : resolutions) {
    std::vector<fs::path> meshes;
    for (const auto& entry : fs::directory_iterator(fs::path(bench) / res))
      if (entry.path().extension() == ".obj") meshes.push_back(entry.path());
    std::sort(meshes.begin(), meshes.end());
    if (meshes.empty()) throw std::runtime_error("no .obj meshes in " + bench + "/" + res);
    std::printf("### %s faces: %zu meshes, %.0f mm on A4, %g mm margins, detail %s%s\n\n",
                res.c_str(), meshes.size(), size_mm, margin_mm, detail.c_str(),
                prefer == FitGoal::Pieces ? ", saving pieces first" : "");
    std::printf(
        "| mesh | sheets | pieces | tabs | strips | smallest label (under 1.5 mm) | s |%s\n",
        with_peer ? " Blender sheets | Blender islands | Blender s |" : "");
    std::printf("|---|---:|---:|---:|---:|---|---:|%s\n", with_peer ? "---:|---:|---:|" : "");
    std::vector<double> pieces, seconds, sheets, peer_sheets, peer_islands;
    int refused = 0, tiled = 0, both = 0, not_more = 0, peer_refused = 0, peer_missing = 0;
    for (const fs::path& path : meshes) {
      const Ours r = run_one(path, size_mm, margin_mm, parse_detail(detail), prefer);
      std::string mesh = r.mesh.substr(0, r.mesh.size() - 4);
      if (!r.error.empty()) {
        ++refused;
        std::printf("| %s | refused: %s | | | | | %.1f |", mesh.c_str(),
                    short_error(r.error).c_str(), r.seconds);
      } else {
        tiled += r.tiled;
        pieces.push_back(r.pieces);
        seconds.push_back(r.seconds);
        sheets.push_back(r.sheets);
        char smallest[64] = "none";  // a print without labels: one piece, no tab
        if (r.labels > 0)
          std::snprintf(smallest, sizeof smallest, "%.2f mm (%zu)", r.smallest_label_mm,
                        r.small_labels);
        std::printf("| %s | %d%s | %d | %zu | %zu | %s | %.1f |", mesh.c_str(), r.sheets,
                    r.tiled ? " tiled" : "", r.pieces, r.tabs, r.strips, smallest, r.seconds);
      }
      if (with_peer) {
        const auto it = peer.find(res + "/" + r.mesh);
        if (it == peer.end()) {
          ++peer_missing;
          std::printf(" – | – | – |");
        } else if (!it->second.error.empty() || it->second.pages <= 0) {
          ++peer_refused;
          std::printf(" refused | | |");
        } else {
          const Peer& p = it->second;
          peer_sheets.push_back(p.pages);
          peer_islands.push_back(p.islands);
          if (r.error.empty()) {
            ++both;
            not_more += r.sheets <= p.pages;
          }
          std::printf(" %d | %d | %.1f |", p.pages, p.islands, p.seconds);
        }
      }
      std::printf("\n");
      std::fflush(stdout);
    }
    std::printf(
        "\npapernet: %d of %zu refused, %d tiled; median %.1f sheets, %.1f pieces, %.2f s "
        "(the overview page, when printed, is not counted as a sheet)\n",
        refused, meshes.size(), tiled, median(sheets), median(pieces), median(seconds));
    if (with_peer)
      std::printf(
          "Blender: %d of %zu refused%s; median %.1f sheets, %.1f islands. Sheets at most "
          "Blender's on %d of the %d meshes both printed (%.0f %%)\n",
          peer_refused, meshes.size(),
          peer_missing ? (", " + std::to_string(peer_missing) + " not run").c_str() : "",
          median(peer_sheets), median(peer_islands), not_more, both,
          both ? 100.0 * not_more / both : 0.0);
    std::printf("\n");
  }
  return 0;
}

}  // namespace
}  // namespace papernet::bench

int main(int argc, char** argv) {
  std::string bench = PAPERNET_SHARED_DATA "/bench", blender, detail = "full";
  std::vector<std::string> resolutions{"400", "1000"};
  double size_mm = 200, margin_mm = papernet::JobOptions{}.margin_mm;
  papernet::FitGoal prefer = papernet::FitGoal::Sheets;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--bench")
      bench = value;
    else if (flag == "--res")
      resolutions = papernet::bench::split(value);
    else if (flag == "--size-mm")
      size_mm = std::stod(value);
    else if (flag == "--detail")
      detail = value;
    else if (flag == "--margin-mm")
      margin_mm = std::stod(value);
    else if (flag == "--blender")
      blender = value;
    else if (flag == "--prefer" && (value == "sheets" || value == "pieces"))
      prefer = value == "pieces" ? papernet::FitGoal::Pieces : papernet::FitGoal::Sheets;
    else {
      std::cerr << "usage: papernet-print-bench [--bench DIR] [--res 400,1000] [--size-mm 200] "
                   "[--detail full|auto|N] [--margin-mm 10] [--prefer sheets|pieces] "
                   "[--blender TSV]\n";
      return 1;
    }
  }
  if (argc % 2 == 0) {
    std::cerr << "papernet-print-bench: " << argv[argc - 1] << " needs a value\n";
    return 1;
  }
  try {
    return papernet::bench::run(bench, resolutions, size_mm, margin_mm, detail, prefer, blender);
  } catch (const std::exception& e) {
    std::cerr << "papernet-print-bench: " << e.what() << "\n";
    return 1;
  }
}
