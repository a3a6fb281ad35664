#pragma once
// The results of `papernet bench`: one CSV row per run, statistics per strategy and resolution,
// and the reports made from them (a Markdown document shaped like the paper's Appendix C table,
// SVG plots against face count).

#include <cmath>
#include <iosfwd>
#include <string>
#include <vector>

namespace papernet::bench {

/// One run of one mesh at one resolution with one strategy (one row of the CSV).
struct BenchRun {
  std::string mesh;      ///< path below the bench folder, e.g. "2000/c3d__igea.obj"
  std::string strategy;  ///< QQ, SEMP, SEQ or TU
  int resolution = 0;    ///< the folder's face count
  int faces = 0;         ///< faces of the mesh the net is of (fewer when approximate)
  unsigned long long seed = 0;
  std::string status;        ///< ok, approx, budget, timeout, crash, invalid, error
  double seconds = 0;        ///< wall-clock of the unfold (load to net check)
  double cpu_seconds = 0;    ///< user + system time of the child process
  long long overlaps = -1;   ///< overlapping pairs left, -1 unknown
  std::string check = "-";   ///< the net checker's verdict: ok, failed, skipped, -
  std::string note;          ///< last line of stderr for runs that are not "ok"
  double hausdorff = 0;      ///< relative Hausdorff distance of an approximation, else 0
  double coverage = -1;      ///< face area / minimum-area box of the net, -1 unknown
  double aspect_ratio = -1;  ///< long / short side of that box, -1 unknown

  bool complete() const { return status == "ok"; }
  /// A net was written: complete or approximate. Everything else counts as a failure.
  bool has_net() const { return status == "ok" || status == "approx"; }
};

/// Writes the CSV (header line, then one row per run; fields quoted when needed).
void write_bench_csv(std::ostream& out, const std::vector<BenchRun>& runs);

/// Reads a CSV written by write_bench_csv or by older versions (columns found by header name;
/// a missing `resolution` column is taken from the mesh path's first folder, missing metrics
/// stay unknown). \throw std::runtime_error naming the line when a row is malformed.
std::vector<BenchRun> read_bench_csv(std::istream& in);

/// Figures of one strategy at one resolution. Times are those of the runs that wrote a net
/// (complete or approximate, as the paper's "timings of successful unfoldings"); NaN when none.
struct BenchGroup {
  std::string strategy;
  int resolution = 0;
  int runs = 0, complete = 0, approx = 0;
  /// Runs refused as having no net at all (status `invalid`, exit 2: e.g. a dual graph that is a
  /// tree whose only unfolding overlaps). On the benchmark's valid meshes that is a proof, not a
  /// failure of the search, so the rates below are also given without them.
  int impossible = 0;
  double min = 0, median = 0, mean = 0, max = 0;                  ///< seconds of runs with a net
  double median_all = 0, mean_all = 0, max_all = 0, p95_all = 0;  ///< seconds of all runs
  double median_cpu = 0, max_cpu = 0;                             ///< CPU s of all runs
  double coverage = 0, aspect_ratio = 0;  ///< means over runs with a net and known metrics
  double hausdorff = 0;                   ///< mean over approximate runs
  /// Mean over the meshes that every progressive strategy (QQ, SEMP, SEQ) in the runs
  /// approximated at this resolution, as the paper's figure; NaN when none (and for TU).
  double hausdorff_shared = 0;
  int shared_approx = 0;  ///< how many such meshes
  double success() const { return runs ? 100.0 * complete / runs : 0; }
  double success_approx() const { return runs ? 100.0 * (complete + approx) / runs : 0; }
  /// success() over the runs not refused as impossible; NaN when every run was.
  double success_possible() const {
    return runs > impossible ? 100.0 * complete / (runs - impossible) : std::nan("");
  }
};

/// Median of the values (mean of the two middle ones for an even count); NaN when empty.
double median(std::vector<double> values);

/// Groups by strategy (in order of first appearance) and resolution (ascending).
std::vector<BenchGroup> summarize(const std::vector<BenchRun>& runs);

/// The two plain-text tables `papernet bench` prints at the end.
std::string text_tables(const std::vector<BenchGroup>& groups);

/// The table in the shape of the paper's Appendix C (rows: value x resolution; columns: our
/// strategies, then the paper's four where it has the figure), in Markdown.
std::string markdown_table(const std::vector<BenchGroup>& groups);

/// What the generated document says about where its data came from.
struct ReportContext {
  std::string csv_link;    ///< link to the CSV, relative to the document ("" = none)
  std::string plots_link;  ///< folder of the SVG plots, relative to the document ("" = none)
  std::string machine;     ///< hardware and OS the runs ran on
  std::string source;      ///< e.g. "binary built from commit abc1234 (Release)"
  std::string command;     ///< the command that regenerates the document
  std::string note;        ///< shown as a quote under the first paragraph ("" = none)
  double time_limit = 0;   ///< seconds per run, 0 unknown
  int jobs = 0;            ///< runs at a time, 0 unknown
  double elapsed = 0;      ///< wall-clock of the whole benchmark, 0 unknown
};

/// The whole generated benchmark document: headline ratios, setup beside the paper's, how to
/// reproduce, the Appendix C table, our plots beside the paper's, failures per mesh.
std::string markdown_report(const std::vector<BenchRun>& runs, const ReportContext& context);

/// Writes the SVG plots (median time on a log scale, success rate with and without
/// approximations, coverage, aspect ratio, Hausdorff) and the paper's Appendix C figures redrawn
/// (paper-*.svg) into `dir` (created when missing). Returns the file names written.
/// \throw std::runtime_error when a file cannot be written
std::vector<std::string> write_plots(const std::vector<BenchGroup>& groups, const std::string& dir);

/// "CPU model, N logical CPUs, RAM, OS" of this machine, read from /proc and /etc/os-release.
std::string describe_machine();

}  // namespace papernet::bench
