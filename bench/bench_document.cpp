// The generated benchmark document and its plots (declared in bench_report.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "bench/bench_report.h"
#include "bench/line_plot.h"
#include "bench/paper_results.h"

namespace papernet::bench {

namespace {

std::string fmt(const char* format, double v) {
  if (!std::isfinite(v)) return "–";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::string color_of(const std::string& strategy) {
  if (strategy == "QQ") return "#7b3294";
  if (strategy == "SEMP") return "#e66101";
  if (strategy == "SEQ") return "#2166ac";
  if (strategy == "TU") return "#1a9641";
  if (strategy == "AUTO") return "#d7191c";
  return "#555555";
}

const BenchGroup* find_group(const std::vector<BenchGroup>& groups, const std::string& strategy,
                             int resolution) {
  for (const BenchGroup& g : groups)
    if (g.strategy == strategy && g.resolution == resolution) return &g;
  return nullptr;
}

std::vector<std::string> strategies_of(const std::vector<BenchGroup>& groups) {
  std::vector<std::string> s;
  for (const BenchGroup& g : groups)
    if (std::find(s.begin(), s.end(), g.strategy) == s.end()) s.push_back(g.strategy);
  return s;
}

std::vector<int> resolutions_of(const std::vector<BenchGroup>& groups) {
  std::vector<int> r;
  for (const BenchGroup& g : groups)
    if (std::find(r.begin(), r.end(), g.resolution) == r.end()) r.push_back(g.resolution);
  std::sort(r.begin(), r.end());
  return r;
}

std::string base_name(const std::string& mesh) {
  std::string name = mesh.substr(mesh.rfind('/') == std::string::npos ? 0 : mesh.rfind('/') + 1);
  if (name.size() > 4 && name.substr(name.size() - 4) == ".obj") name.resize(name.size() - 4);
  return name;
}

// "**132× faster**", "**1.6× faster**" or "**2.0× slower**" for paper time / our time.
std::string speedup(double ratio) {
  if (!std::isfinite(ratio) || ratio <= 0) return "–";
  if (ratio >= 1) return "**" + fmt(ratio >= 10 ? "%.0f" : "%.1f", ratio) + "×** faster";
  return "**" + fmt("%.1f", 1 / ratio) + "×** slower";
}

// One plot per figure: ours from the groups, or the paper's from its table.
LinePlot figure(const std::vector<BenchGroup>& groups, const std::string& title,
                const std::string& y_label, double (*value)(const BenchGroup&)) {
  LinePlot plot;
  plot.title = title;
  plot.x_label = "Number of faces";
  plot.y_label = y_label;
  for (const std::string& s : strategies_of(groups)) {
    PlotSeries series{s, color_of(s), false, {}};
    for (const BenchGroup& g : groups)
      if (g.strategy == s) series.points.push_back({g.resolution, value(g)});
    plot.series.push_back(series);
  }
  return plot;
}

LinePlot paper_figure(const std::string& title, const std::string& y_label,
                      double (*value)(const PaperResult&)) {
  LinePlot plot;
  plot.title = title;
  plot.x_label = "Number of faces";
  plot.y_label = y_label;
  for (const char* s : {"QQ", "SEMP", "SEQ", "TU"}) {
    PlotSeries series{"paper " + paper_strategy_name(s), color_of(s), true, {}};
    for (const PaperResult& p : paper_results())
      if (p.strategy == s) series.points.push_back({p.resolution, value(p)});
    plot.series.push_back(series);
  }
  return plot;
}

// A success-rate axis: from a multiple of 5 below the lowest value up to exactly 100 %.
void percent_axis(LinePlot& plot) {
  double low = 100;
  for (const PlotSeries& s : plot.series)
    for (const auto& [x, y] : s.points)
      if (std::isfinite(y)) low = std::min(low, y);
  plot.fix_y = true;
  plot.y_max = 100;
  plot.y_min = std::max(0.0, std::floor(low / 5 - 1e-9) * 5);
  if (plot.y_min >= 100) plot.y_min = 95;
}

}  // namespace

std::vector<std::string> write_plots(const std::vector<BenchGroup>& groups,
                                     const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw std::runtime_error("cannot create the folder " + dir);
  std::vector<std::pair<std::string, LinePlot>> plots;
  LinePlot time = figure(groups, "Median time of runs that wrote a net (log scale)", "Seconds",
                         [](const BenchGroup& g) { return g.median; });
  time.log_y = true;
  plots.push_back({"median-time.svg", time});
  LinePlot approx = figure(groups, "Success rate incl. approximations", "Success (%)",
                           [](const BenchGroup& g) { return g.success_approx(); });
  percent_axis(approx);
  plots.push_back({"success-approx.svg", approx});
  LinePlot regular = figure(groups, "Success rate, complete nets only", "Success (%)",
                            [](const BenchGroup& g) { return g.success(); });
  percent_axis(regular);
  plots.push_back({"success.svg", regular});
  plots.push_back({"coverage.svg", figure(groups, "Mean coverage", "Coverage (%)",
                                          [](const BenchGroup& g) { return 100 * g.coverage; })});
  plots.push_back({"aspect-ratio.svg", figure(groups, "Mean aspect ratio", "Aspect ratio",
                                              [](const BenchGroup& g) { return g.aspect_ratio; })});
  plots.push_back(
      {"hausdorff.svg", figure(groups, "Mean relative Hausdorff distance of approximations",
                               "Hausdorff distance (% of diagonal)", [](const BenchGroup& g) {
                                 return g.approx ? 100 * g.hausdorff
                                                 : std::numeric_limits<double>::quiet_NaN();
                               })});
  plots.push_back({"hausdorff-shared.svg",
                   figure(groups, "Mean relative Hausdorff distance, shared approximations",
                          "Hausdorff distance (% of diagonal)",
                          [](const BenchGroup& g) { return 100 * g.hausdorff_shared; })});
  LinePlot paper_time = paper_figure("Paper: median time (log scale)", "Seconds",
                                     [](const PaperResult& p) { return p.median; });
  paper_time.log_y = true;
  plots.push_back({"paper-median-time.svg", paper_time});
  LinePlot paper_approx = paper_figure("Paper: success rate incl. approximations", "Success (%)",
                                       [](const PaperResult& p) { return p.success_approx; });
  percent_axis(paper_approx);
  plots.push_back({"paper-success-approx.svg", paper_approx});
  LinePlot paper_regular = paper_figure("Paper: success rate, complete nets only", "Success (%)",
                                        [](const PaperResult& p) { return p.success; });
  percent_axis(paper_regular);
  plots.push_back({"paper-success.svg", paper_regular});

  std::vector<std::string> written;
  for (const auto& [name, plot] : plots) {
    const std::string path = (fs::path(dir) / name).string();
    std::ofstream out(path);
    out << write_line_plot(plot);
    if (!out) throw std::runtime_error("cannot write " + path);
    written.push_back(name);
  }
  return written;
}

std::string markdown_report(const std::vector<BenchRun>& runs, const ReportContext& ctx) {
  const std::vector<BenchGroup> groups = summarize(runs);
  const std::vector<std::string> strategies = strategies_of(groups);
  const std::vector<int> resolutions = resolutions_of(groups);
  std::ostringstream out;
  out << "# Benchmarks\n\n"
      << "<!-- Generated by `" << (ctx.command.empty() ? "papernet-bench" : ctx.command)
      << "`; do not edit by hand, rerun it. The hand-written analysis lives in performance.md. "
         "-->\n\n";
  if (runs.empty()) return out.str() + "No runs.\n";

  std::map<std::string, int> meshes;
  int failed = 0, checked = 0, check_failed = 0;
  std::map<std::string, int> by_status;
  for (const BenchRun& r : runs) {
    ++meshes[base_name(r.mesh)];
    failed += !r.has_net();
    checked += r.check == "ok";
    check_failed += r.check == "failed";
    ++by_status[r.status];
  }
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  out << "Generated " << date << " from " << runs.size() << " runs (" << meshes.size()
      << " meshes × " << resolutions.size() << " resolutions × " << strategies.size()
      << " strategies)";
  if (!ctx.csv_link.empty())
    out << ", every run in [" << ctx.csv_link << "](" << ctx.csv_link << ")";
  out << ". What the figures mean, where the time goes, what fails and why and what is planned: "
         "[performance.md](performance.md).\n\n";
  if (!ctx.note.empty()) out << "> " << ctx.note << "\n\n";

  // Headline ratios at 2,000 faces (or the largest resolution measured).
  const int h = std::find(resolutions.begin(), resolutions.end(), 2000) != resolutions.end()
                    ? 2000
                    : resolutions.back();
  out << "## Headline (" << h << " faces)\n\n";
  for (const std::string& s : strategies) {
    const BenchGroup* g = find_group(groups, s, h);
    const PaperResult* p = paper_result(s, h);
    if (!g) continue;
    out << "- **" << s << "**: median " << fmt("%.3f", g->median) << " s";
    if (p)
      out << " vs the paper's " << paper_strategy_name(s) << " " << fmt("%.3f", p->median) << " s ("
          << speedup(p->median / g->median) << ")";
    out << "; success " << fmt("%.1f", g->success()) << " % complete, "
        << fmt("%.1f", g->success_approx()) << " % incl. approximations";
    if (g->impossible)
      out << " (" << g->impossible << " of " << g->runs
          << " inputs refused as impossible; complete: " << fmt("%.1f", g->success_possible())
          << " % of the others)";
    if (p)
      out << " (paper " << fmt("%.1f", p->success) << " %, " << fmt("%.1f", p->success_approx)
          << " %)";
    out << ".\n";
  }
  // Our TU's median over QQ's and over the default's (AUTO, QQ finished by TU when it stops).
  for (const char* s : {"AUTO", "QQ"}) {
    if (!find_group(groups, s, h) || !find_group(groups, "TU", h)) continue;
    const double ratio = find_group(groups, "TU", h)->median / find_group(groups, s, h)->median;
    out << "- **" << s << " vs our TU**: our TU's median is " << fmt("%.2f", ratio) << "× " << s
        << "'s at " << h << " faces";
    if (paper_result(s, h) && paper_result("TU", h))
      out << " (paper: TU "
          << fmt("%.2f", paper_result("TU", h)->median / paper_result(s, h)->median) << "× Q/Q)";
    out << "; per resolution:";
    for (int r : resolutions) {
      const BenchGroup *q = find_group(groups, s, r), *t = find_group(groups, "TU", r);
      if (q && t) out << " " << r << ": " << fmt("%.2f", t->median / q->median) << "×";
    }
    out << ".\n";
  }
  if (find_group(groups, "AUTO", h) && find_group(groups, "TU", h)) {
    out << "- **Complete nets, AUTO / TU** per resolution:";
    for (int r : resolutions) {
      const BenchGroup *a = find_group(groups, "AUTO", r), *t = find_group(groups, "TU", r);
      if (a && t) out << " " << r << ": " << a->complete << " / " << t->complete;
    }
    out << " (of " << find_group(groups, "TU", h)->runs << " meshes each).\n";
  }
  out << "- **Success over all resolutions**:";
  for (const std::string& s : strategies) {
    int n = 0, complete = 0, with_net = 0;
    for (const BenchGroup& g : groups)
      if (g.strategy == s) n += g.runs, complete += g.complete, with_net += g.complete + g.approx;
    out << " " << s << " " << fmt("%.1f", 100.0 * complete / n) << " % complete / "
        << fmt("%.1f", 100.0 * with_net / n) << " % incl. approximations;";
  }
  out << " " << failed << " of " << runs.size() << " runs failed (";
  bool first = true;
  for (const auto& [status, n] : by_status)
    if (status != "ok" && status != "approx")
      out << (first ? "" : ", ") << n << " " << status, first = false;
  out << "). " << checked << " nets passed the independent net checker, " << check_failed
      << " failed it.\n\n";

  out << "## Setup\n\n| | ours | paper |\n|---|---|---|\n"
      << "| machine | " << (ctx.machine.empty() ? describe_machine() : ctx.machine);
  if (ctx.jobs > 0) out << "; " << ctx.jobs << " runs at a time, each a child process";
  out << " | " << kPaperMachine << " |\n"
      << "| data | " << meshes.size() << " meshes of `../shared/data/bench` at "
      << resolutions.size() << " resolutions | " << kPaperData << " |\n"
      << "| time limit | "
      << (ctx.time_limit > 0 ? fmt("%g", ctx.time_limit) + " s per run; a run over it fails"
                             : std::string("unknown"))
      << " | none reported |\n"
      << "| timings | wall-clock of `papernet unfold` from loading to the net check, of runs "
         "that wrote a net (complete or approximate) | \"timings of successful unfoldings\" |\n";
  if (!ctx.source.empty()) out << "| build | " << ctx.source << " | C++ |\n";
  if (ctx.elapsed > 0)
    out << "| duration | " << fmt("%.1f", ctx.elapsed / 60) << " min for all runs | – |\n";
  out << "\nThe two machines differ (CPU, data set size and content, time limit): the ratios "
         "are an indication, not a controlled comparison.\n\n"
      << "## Reproduce\n\n```sh\n"
      << (ctx.command.empty() ? "papernet-bench ../shared/data/bench --csv runs.csv" : ctx.command)
      << "\n```\n\nNeeds `../shared/data` (see its README). The script builds papernet "
         "(Release), runs every mesh at every resolution with every strategy, each in its own "
         "`papernet unfold` process (a crash or a timeout counts as a failure), writes the CSV, "
         "then this document and the plots from the CSV. `FROM_CSV=docs/benchmarks/runs.csv "
         "scripts/benchmarks.sh` remakes the document and plots from the CSV alone.\n\n";

  out << "## Results in the shape of the paper's Appendix C table\n\n"
      << "Ours per strategy, then the paper's (2,800 meshes; coverage, aspect ratio and "
         "Hausdorff distance appear in the paper only as figures, without numbers). Runs that "
         "failed count in the success rates, not in the timings.\n\n"
      << markdown_table(groups) << "\n";

  if (!ctx.plots_link.empty()) {
    const std::string d = ctx.plots_link + "/";
    const auto img = [&](const std::string& file, const std::string& alt) {
      return "![" + alt + "](" + d + file + ")";
    };
    out << "## Figures: ours (left), the paper's (right)\n\n"
        << "The paper's curves are redrawn from its Appendix C table; for coverage, aspect ratio "
           "and Hausdorff distance it gives figures only, summarised in words.\n\n"
        << "| ours | paper |\n|---|---|\n"
        << "| " << img("median-time.svg", "median time") << " | "
        << img("paper-median-time.svg", "paper median time") << " |\n"
        << "| " << img("success-approx.svg", "success incl. approximations") << " | "
        << img("paper-success-approx.svg", "paper success incl. approximations") << " |\n"
        << "| " << img("success.svg", "success") << " | "
        << img("paper-success.svg", "paper success") << " |\n"
        << "| " << img("coverage.svg", "coverage")
        << " | Paper (Fig. Coverage): 15–30 %, Q/Q, SE/MP, SE/Q and TU almost the same, same "
           "trend. |\n"
        << "| " << img("aspect-ratio.svg", "aspect ratio")
        << " | Paper (Fig. AspectRatios): 1.5–1.8; TU falls with the face count, the progressive "
           "variants stay close to 1.8. |\n"
        << "| " << img("hausdorff-shared.svg", "Hausdorff, shared approximations")
        << " | Paper (Fig. HausdorffSchnitt), the same measure (mean over the meshes that all "
           "three progressive variants approximated): 0–9 % at low resolutions, near 0 % at "
           "2,000 faces, Q/Q lowest. |\n"
        << "| " << img("hausdorff.svg", "Hausdorff")
        << " | Not in the paper: the mean over each strategy's own approximations (more meshes, "
           "but a different set per strategy). |\n\n";
  }

  // Failures and timeouts per mesh: mesh -> strategy -> status -> resolutions.
  std::map<std::string, std::map<std::string, std::map<std::string, std::vector<int>>>> fails;
  std::map<std::string, int> fail_count;
  for (const BenchRun& r : runs)
    if (!r.has_net()) {
      fails[base_name(r.mesh)][r.strategy][r.status].push_back(r.resolution);
      ++fail_count[base_name(r.mesh)];
    }
  out << "## Failures and timeouts per mesh\n\n";
  if (fails.empty()) {
    out << "None: every run wrote a net.\n";
  } else {
    std::vector<std::pair<int, std::string>> order;
    for (const auto& [mesh, n] : fail_count) order.push_back({-n, mesh});
    std::sort(order.begin(), order.end());
    out << "Status: `budget` no overlap-free net in one piece within the time limit (at once "
           "when no move exists, e.g. a mesh whose dual graph is a tree; the run then writes the "
           "mesh in pieces grown from single faces), `timeout` killed after the limit "
           "plus a grace period, `invalid` the mesh was rejected, `crash`/`error` see the CSV's "
           "note.\n\n"
        << "| mesh | failed runs | strategy: status at resolutions |\n|---|---:|---|\n";
    for (const auto& [minus_n, mesh] : order) {
      out << "| `" << mesh << "` | " << -minus_n << " of " << meshes[mesh] << " |";
      const char* sep = " ";
      for (const auto& [s, statuses] : fails[mesh]) {
        out << sep << s << ":";
        const char* sep2 = " ";
        for (auto [status, at] : statuses) {
          std::sort(at.begin(), at.end());
          out << sep2 << status << " at";
          for (std::size_t i = 0; i < at.size(); ++i) out << (i ? ", " : " ") << at[i];
          sep2 = ", ";
        }
        sep = "; ";
      }
      out << " |\n";
    }
  }
  return out.str();
}

}  // namespace papernet::bench
