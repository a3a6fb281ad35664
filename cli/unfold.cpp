// `papernet unfold FILE [--strategy QQ|SEMP|SEQ|TU] [--target-faces N] -o OUT [-o OUT]...
//  [--seed N] [--time-limit S] [print options]`
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iostream>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "api/net_json.h"
#include "cli/commands.h"
#include "core/errors.h"
#include "core/io/load.h"
#include "core/mesh/validate.h"
#include "core/tabs/tab_clearance_report.h"
#include "core/unfold/net_check.h"
#include "core/unfold/net_metrics.h"
#include "core/unfold/progressive.h"
#include "core/unfold/unfolding.h"
#include "print/print_output.h"

namespace papernet::cli {

namespace {

// The tab room report's threshold for a flat vertex (angle defect); only its flat-leaf counts
// depend on it, and those are not printed.
constexpr double kFlatDefect = 10 * std::numbers::pi / 180;

constexpr const char* kUsage =
    "usage: papernet unfold FILE [--strategy QQ|SEMP|SEQ|TU] [--target-faces N] -o OUT\n"
    "                            [-o OUT]... [--seed N] [--time-limit S] [--simplify N]\n"
    "                            [print options]\n"
    "QQ (default), SEMP, SEQ: progressive unfolding after collapsing to N faces (default\n"
    "F/10 + sqrt(F)(1+genus)); TU: Tabu Unfolding of the full mesh.\n"
    "--simplify N unfolds and prints a low-poly version of the mesh instead: collapsed to N\n"
    "faces first (by the strategy's collapses, QQ's for TU). Fewer, larger faces leave room\n"
    "for more glue tabs (dense, smooth meshes keep glue strips); the net is then approximate,\n"
    "with its Hausdorff distance to the input.\n"
    "OUT is chosen by extension: .json (papernet.net/1), .svg (one page, or OUT-1.svg ... per\n"
    "page), .pdf (one page per tile), .glb / .obj (the mesh the net folds into).\n"
    "exit codes: 0 net written (also an approximate one: a net of a coarser mesh, said on\n"
    "stderr and in the JSON), 2 input cannot be unfolded, 3 no overlap-free net within the\n"
    "budget, 1 other errors. Prints one summary line (key=value) on stdout.\n";

}  // namespace

int unfold(int argc, char** argv) {
  std::string file, strategy = "QQ";
  std::vector<std::string> outputs;
  TabuOptions options;
  OutputOptions print;
  std::size_t target_faces = 0, simplify = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    try {
      if (arg == "--help" || arg == "-h") {
        std::cout << kUsage << "print options:\n" << output_options_help();
        return 0;
      } else if (arg == "--strategy") {
        strategy = value();
      } else if (arg == "-o" || arg == "--output") {
        outputs.push_back(value());
        const std::string& o = outputs.back();
        if (!is_print_output(o) && !(o.size() > 5 && o.substr(o.size() - 5) == ".json"))
          throw std::invalid_argument("unknown output type '" + o +
                                      "': use .json, .svg, .pdf, .glb or .obj");
      } else if (arg == "--target-faces") {
        const long long n = std::stoll(value());
        if (n < 1) throw std::invalid_argument("--target-faces must be at least 1");
        target_faces = static_cast<std::size_t>(n);
      } else if (arg == "--simplify") {
        const long long n = std::stoll(value());
        if (n < 4) throw std::invalid_argument("--simplify must be at least 4 faces");
        simplify = static_cast<std::size_t>(n);
      } else if (arg == "--seed") {
        options.seed = std::stoull(value());
      } else if (arg == "--time-limit") {
        options.time_limit_seconds = std::stod(value());
      } else if (arg.starts_with("--") && i + 1 < argc &&
                 apply_output_option(arg, argv[i + 1], print)) {
        ++i;
      } else if (!arg.empty() && arg[0] == '-') {
        throw std::invalid_argument("unknown option " + arg);
      } else if (file.empty()) {
        file = arg;
      } else {
        throw std::invalid_argument("more than one input file");
      }
    } catch (const std::exception& e) {
      std::cerr << "papernet unfold: " << e.what() << "\n" << kUsage;
      return 1;
    }
  }
  if (file.empty() || outputs.empty()) {
    std::cerr << kUsage;
    return 1;
  }
  const std::optional<CollapseStrategy> collapse = parse_collapse_strategy(strategy);
  if (strategy != "TU" && !collapse) {
    std::cerr << "papernet unfold: unknown strategy '" << strategy << "' (QQ, SEMP, SEQ or TU)\n";
    return 1;
  }
  if (collapse) strategy = strategy_name(*collapse);

  const auto start = std::chrono::steady_clock::now();
  NetDocument doc;
  UnfoldResult result;
  try {
    LoadedMesh loaded = load_mesh_file(file);
    const ValidationReport report = validate(loaded);
    if (!report.unfoldable()) throw InvalidInputException(report.reason());
    doc.input.vertices = report.vertices;
    doc.input.faces = report.faces;
    doc.input.genus = static_cast<int>(report.genus);
    doc.input.boundaries = report.boundary_loops;
    Progress quiet;
    // A low-poly version to print instead of the input: the net is then approximate, its
    // distance measured to the input.
    std::optional<Mesh> input;
    if (std::optional<Mesh> simple =
            simplify_mesh(loaded.mesh, collapse.value_or(CollapseStrategy::QQ), simplify, quiet)) {
      input = std::exchange(loaded.mesh, std::move(*simple));
      std::cerr << "papernet unfold: " << file << ": simplified from " << input->faces.size()
                << " to " << loaded.mesh.faces.size() << " faces\n";
    }
    if (collapse) {
      ProgressiveOptions progressive;
      progressive.strategy = *collapse;
      progressive.target_faces = target_faces;
      progressive.tabu = options;
      ProgressiveResult p = unfold_progressive(loaded.mesh, progressive, quiet);
      result.net = std::move(p.net);
      result.overlap_free = p.overlap_free;
      result.overlaps = p.overlaps;
      result.stats = p.stats;
      if (p.overlap_free && !p.complete) {
        doc.result = "approximate";
        doc.metrics.hausdorff = p.hausdorff;
      }
      doc.mesh = std::move(p.mesh);
    } else {
      result = unfold_tabu(loaded.mesh, options, quiet);
      doc.mesh = std::move(loaded.mesh);
    }
    if (input && result.overlap_free) {
      doc.result = "approximate";
      doc.metrics.hausdorff = approximation_distance(*input, doc.mesh);
    }
  } catch (const IOException& e) {
    std::cerr << "papernet unfold: " << file << ": " << e.what() << "\n";
    return 2;
  } catch (const InvalidInputException& e) {
    std::cerr << "papernet unfold: " << file << ": cannot be unfolded: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "papernet unfold: " << file << ": " << e.what() << "\n";
    return 1;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "result=" << (result.overlap_free ? doc.result : "failed")
            << " faces=" << doc.mesh.faces.size() << " input_faces=" << doc.input.faces
            << " hausdorff=" << doc.metrics.hausdorff << " overlaps=" << result.overlaps
            << " iterations=" << result.stats.iterations << " seconds=" << seconds;
  if (!result.overlap_free) {
    std::cout << " check=skipped\n";
    std::cerr << "papernet unfold: " << file << ": no overlap-free net within the budget ("
              << result.overlaps << " overlapping pairs left after " << result.stats.iterations
              << " iterations)\n";
    return 3;
  }
  // Printing with tabs: first give the cut edges room for them (docs/tabs.md). The net JSON
  // written alongside is this net too, so that every output shows the same cuts.
  const bool prints = std::any_of(outputs.begin(), outputs.end(), [](const std::string& o) {
    const std::string ext = o.size() > 4 ? o.substr(o.size() - 4) : "";
    return ext == ".svg" || ext == ".pdf" || ext == ".SVG" || ext == ".PDF";
  });
  std::optional<NetCheckReport> checked;  // of result.net, when the tab-room pass changed it
  if (prints && print.print.tabs == TabMode::Auto && print.print.tab_height_mm > 0 &&
      print.print.tab_room) {
    const auto t0 = std::chrono::steady_clock::now();
    Progress quiet;
    TabClearanceResult room = make_tab_room(doc.mesh, result.net, print.print, quiet);
    const double room_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (room.moves > 0) {
      if (NetCheckReport again = check_net(doc.mesh, room.net); again.ok()) {
        result.net = std::move(room.net);
        checked = std::move(again);
      } else {
        std::cerr << "papernet unfold: internal error, the net with tab room fails its check ("
                  << again.summary() << "); printing the unfolder's net\n";
        room.blocked_after = room.blocked_before;
      }
    }
    std::cerr << "papernet unfold: tab room: " << room.blocked_before << " -> "
              << room.blocked_after << " cut edges without room for a tab (" << room.moves
              << " moves, " << room.kicks << " kicks, " << room.evaluations << " evaluated, "
              << room_seconds << " s)\n";
    if (room.blocked_after > 0) {
      // Why edges stay without room: a leaf of the cut tree at a nearly flat vertex always
      // lacks it (core/tab_clearance_report.h), and a dense mesh has few vertices where a leaf
      // can have it.
      const TabRoomReport why = describe_tab_room(
          doc.mesh, result.net, tab_clearance_options(doc.mesh, print.print), kFlatDefect);
      std::cerr << "papernet unfold: tab room: " << why.leaves_without_room_blocked << " of the "
                << why.blocked << " end at a leaf of the cut tree where no leaf has room (only "
                << why.leaf_room_vertices << " of " << why.interior_vertices
                << " vertices are sharp enough at this size); print larger (--size) or "
                   "simplify (--simplify N faces) for fewer glue strips\n";
    }
  }
  const NetCheckReport check = checked ? std::move(*checked) : check_net(doc.mesh, result.net);
  const NetBoxMetrics box = net_metrics(doc.mesh, result.net);
  std::cout << " coverage=" << box.coverage << " aspect_ratio=" << box.aspect_ratio
            << " check=" << (check.ok() ? "ok" : "failed") << "\n";
  if (!check.ok()) {
    std::cerr << "papernet unfold: internal error, the net fails its check: " << check.summary()
              << "\n";
    return 1;
  }
  if (doc.result == "approximate")
    std::cerr << "papernet unfold: " << file << ": approximate result: the net folds into a "
              << "coarser mesh of " << doc.mesh.faces.size() << " of " << doc.input.faces
              << " faces, Hausdorff distance " << doc.metrics.hausdorff
              << " of the bounding-box diagonal\n";
  doc.strategy = strategy;
  doc.net = std::move(result.net);
  doc.metrics.faces = doc.mesh.faces.size();
  doc.metrics.overlaps = result.overlaps;
  doc.metrics.seconds = seconds;
  doc.metrics.coverage = box.coverage;
  doc.metrics.aspect_ratio = box.aspect_ratio;
  for (const std::string& output : outputs) {
    if (is_print_output(output)) {
      try {
        const WrittenOutput w = write_output_file(output, doc.mesh, doc.net, print);
        for (const std::string& written : w.files)
          std::cerr << "papernet unfold: wrote " << written << "\n";
        if (w.pages > 0)
          std::cerr << "papernet unfold: " << output << ": " << w.pages << " page(s), " << w.tabs
                    << " glue tabs, " << w.strips << " glue strips, " << w.tabs_omitted
                    << " cut edges without glue\n";
      } catch (const std::exception& e) {
        std::cerr << "papernet unfold: " << output << ": " << e.what() << "\n";
        return 1;
      }
      continue;
    }
    std::ofstream out(output, std::ios::binary);
    out << write_net_json(doc) << "\n";
    if (!out) {
      std::cerr << "papernet unfold: cannot write " << output << "\n";
      return 1;
    }
  }
  return 0;
}

}  // namespace papernet::cli
