// The benchmark's reports: CSV round trip, statistics, the Appendix C Markdown table, the SVG
// plots (parsed by xmllint, rendered by rsvg-convert), the progress line, and a small real
// `papernet-bench` run end to end.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "bench/bench_progress.h"
#include "bench/bench_report.h"
#include "bench/bench_run.h"
#include "bench/line_plot.h"
#include "bench/paper_results.h"
#include "tests/support/paths.h"

namespace papernet::bench {
namespace {

namespace fs = std::filesystem;

int run_tool(const std::string& tool, const std::string& args) {
  if (std::system(("command -v " + tool + " >/dev/null 2>&1").c_str()) != 0) return -1;
  return std::system((tool + " " + args + " >/dev/null 2>&1").c_str());
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("papernet_bench_report_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

BenchRun make_run(const std::string& mesh, const std::string& strategy, int resolution,
                  const std::string& status, double seconds, double coverage = -1,
                  double aspect = -1, double hausdorff = 0) {
  BenchRun r;
  r.mesh = std::to_string(resolution) + "/" + mesh + ".obj";
  r.strategy = strategy;
  r.resolution = resolution;
  r.faces = status == "approx" ? resolution / 2 : resolution;
  r.status = status;
  r.seconds = seconds;
  r.cpu_seconds = seconds;
  r.coverage = coverage;
  r.aspect_ratio = aspect;
  r.hausdorff = hausdorff;
  r.check = status == "ok" || status == "approx" ? "ok" : "skipped";
  r.note = status == "ok" ? "" : "papernet unfold: x.obj: \"quoted\", with a comma";
  return r;
}

// A synthetic benchmark: two strategies, two resolutions, five meshes; QQ at 100 has one
// timeout, one budget failure and one approximation.
std::vector<BenchRun> synthetic() {
  return {
      make_run("a", "QQ", 100, "ok", 0.50, 0.20, 1.5),
      make_run("b", "QQ", 100, "approx", 0.10, 0.30, 2.5, 0.02),
      make_run("c", "QQ", 100, "ok", 0.30, 0.25, 2.0),
      make_run("d", "QQ", 100, "timeout", 30.0),
      make_run("e", "QQ", 100, "budget", 10.0),
      make_run("a", "TU", 100, "ok", 0.20, 0.22, 1.8),
      make_run("b", "TU", 100, "ok", 0.40, 0.24, 1.6),
      make_run("c", "TU", 100, "ok", 0.60, 0.26, 1.4),
      make_run("d", "TU", 100, "ok", 0.80, 0.28, 1.2),
      make_run("e", "TU", 100, "crash", 0.01),
      make_run("a", "QQ", 2000, "ok", 4.0, 0.21, 1.7),
      make_run("b", "QQ", 2000, "ok", 2.0, 0.23, 1.9),
      make_run("a", "TU", 2000, "ok", 8.0, 0.19, 1.3),
      make_run("b", "TU", 2000, "approx", 6.0, 0.17, 1.1, 0.001),  // TU never approximates; fine
  };
}

// The median computed another way than the code under test: nth_element on a copy.
double reference_median(std::vector<double> v) {
  const std::size_t n = v.size();
  std::nth_element(v.begin(), v.begin() + static_cast<long>(n / 2), v.end());
  const double upper = v[n / 2];
  if (n % 2) return upper;
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + static_cast<long>(n / 2)));
}

TEST(BenchReport, CsvRoundTripKeepsEveryField) {
  const std::vector<BenchRun> runs = synthetic();
  std::stringstream csv;
  write_bench_csv(csv, runs);
  const std::vector<BenchRun> back = read_bench_csv(csv);
  ASSERT_EQ(back.size(), runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i) {
    EXPECT_EQ(back[i].mesh, runs[i].mesh);
    EXPECT_EQ(back[i].strategy, runs[i].strategy);
    EXPECT_EQ(back[i].resolution, runs[i].resolution);
    EXPECT_EQ(back[i].faces, runs[i].faces);
    EXPECT_EQ(back[i].status, runs[i].status);
    EXPECT_EQ(back[i].note, runs[i].note);
    EXPECT_DOUBLE_EQ(back[i].seconds, runs[i].seconds);
    EXPECT_DOUBLE_EQ(back[i].coverage, runs[i].coverage);
    EXPECT_DOUBLE_EQ(back[i].aspect_ratio, runs[i].aspect_ratio);
    EXPECT_DOUBLE_EQ(back[i].hausdorff, runs[i].hausdorff);
  }
}

TEST(BenchReport, ReadsOlderCsvWithoutResolutionColumn) {
  // The layout of docs/benchmarks/all-strategies-3ca6ede.csv: `faces` is the net's face count
  // (20 for an approximation of a 100-face mesh), the folder gives the resolution.
  std::stringstream csv(
      "mesh,faces,strategy,seed,status,seconds,cpu_seconds,overlaps,net_check,note,hausdorff\n"
      "100/x.obj,20,QQ,1,approx,0.5,0.6,0,ok,\"note, with comma\",0.01\n"
      "2000/y.obj,2000,TU,1,ok,1.5,1.6,0,ok,,0\n");
  const std::vector<BenchRun> runs = read_bench_csv(csv);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].resolution, 100);
  EXPECT_EQ(runs[0].faces, 20);
  EXPECT_EQ(runs[0].note, "note, with comma");
  EXPECT_EQ(runs[1].resolution, 2000);
  EXPECT_LT(runs[1].coverage, 0) << "unknown metrics stay unknown";
}

TEST(BenchReport, MalformedCsvNamesTheLine) {
  std::stringstream short_row("mesh,strategy,status,seconds\n100/a.obj,QQ,ok,1\n100/b.obj,QQ\n");
  try {
    read_bench_csv(short_row);
    FAIL() << "a short row must be rejected";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
  std::stringstream bad_number("mesh,strategy,status,seconds\n100/a.obj,QQ,ok,fast\n");
  EXPECT_THROW(read_bench_csv(bad_number), std::runtime_error);
  std::stringstream no_column("mesh,strategy\n100/a.obj,QQ\n");
  EXPECT_THROW(read_bench_csv(no_column), std::runtime_error);
}

TEST(BenchReport, FailedAndTimedOutRunsCountAsFailures) {
  const std::vector<BenchRun> runs = synthetic();
  const std::vector<BenchGroup> groups = summarize(runs);
  ASSERT_EQ(groups.size(), 4u);
  for (const BenchGroup& g : groups) {
    std::vector<double> net_seconds, coverage;
    int n = 0, complete = 0, with_net = 0;
    for (const BenchRun& r : runs) {
      if (r.strategy != g.strategy || r.resolution != g.resolution) continue;
      ++n;
      const bool net = r.status == "ok" || r.status == "approx";
      complete += r.status == "ok";
      with_net += net;
      if (net) net_seconds.push_back(r.seconds), coverage.push_back(r.coverage);
    }
    SCOPED_TRACE(g.strategy + " " + std::to_string(g.resolution));
    EXPECT_EQ(g.runs, n);
    EXPECT_DOUBLE_EQ(g.success(), 100.0 * complete / n);
    EXPECT_DOUBLE_EQ(g.success_approx(), 100.0 * with_net / n);
    EXPECT_DOUBLE_EQ(g.median, reference_median(net_seconds));
    EXPECT_DOUBLE_EQ(g.min, *std::min_element(net_seconds.begin(), net_seconds.end()));
    EXPECT_DOUBLE_EQ(g.max, *std::max_element(net_seconds.begin(), net_seconds.end()));
    double sum = 0;
    for (double c : coverage) sum += c;
    EXPECT_NEAR(g.coverage, sum / static_cast<double>(coverage.size()), 1e-12);
  }
  // QQ at 100: the timeout (30 s) and the budget failure (10 s) are failures, and their times
  // stay out of the timings.
  const BenchGroup& qq = groups[0];
  EXPECT_EQ(qq.strategy, "QQ");
  EXPECT_EQ(qq.resolution, 100);
  EXPECT_DOUBLE_EQ(qq.success(), 40.0);
  EXPECT_DOUBLE_EQ(qq.success_approx(), 60.0);
  EXPECT_LT(qq.max, 1.0);
  EXPECT_DOUBLE_EQ(qq.max_all, 30.0);
  EXPECT_DOUBLE_EQ(qq.hausdorff, 0.02);
  // QQ is the only progressive strategy here, so its shared approximations are its own.
  EXPECT_DOUBLE_EQ(qq.hausdorff_shared, 0.02);
  EXPECT_EQ(qq.shared_approx, 1);
  EXPECT_TRUE(std::isnan(groups[2].hausdorff_shared)) << "TU has no shared approximations";
  BenchRun timeout = make_run("z", "TU", 100, "timeout", 99);
  EXPECT_FALSE(timeout.has_net());
}

TEST(BenchReport, InputsRefusedAsImpossibleAreCountedApart) {
  // TU at 100: 3 nets, 1 budget failure, 1 input refused as impossible (exit 2).
  const std::vector<BenchRun> runs = {
      make_run("a", "TU", 100, "ok", 1, 0.2, 2), make_run("b", "TU", 100, "ok", 1, 0.2, 2),
      make_run("c", "TU", 100, "ok", 1, 0.2, 2), make_run("d", "TU", 100, "budget", 60),
      make_run("e", "TU", 100, "invalid", 0.01),
  };
  const std::vector<BenchGroup> groups = summarize(runs);
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].impossible, 1);
  EXPECT_DOUBLE_EQ(groups[0].success(), 60.0) << "the refused input still fails the plain rate";
  EXPECT_DOUBLE_EQ(groups[0].success_possible(), 75.0);
  const std::string md = markdown_table(groups);
  EXPECT_NE(md.find("| Inputs refused as impossible (exit 2) | 100 | 1 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| Regular, of the inputs not refused (where any were) | 100 | 75.0 |"),
            std::string::npos)
      << md;
  // Without refused inputs the two rows stay out of the table.
  EXPECT_EQ(markdown_table(summarize({runs[0], runs[3]})).find("refused"), std::string::npos);
}

TEST(BenchReport, SharedHausdorffIsOverMeshesEveryProgressiveStrategyApproximated) {
  // x: approximated by QQ and SEMP (shared); y: only by QQ (SEMP complete): not shared.
  const std::vector<BenchRun> runs = {
      make_run("x", "QQ", 400, "approx", 1, 0.2, 2, 0.010),
      make_run("x", "SEMP", 400, "approx", 1, 0.2, 2, 0.030),
      make_run("y", "QQ", 400, "approx", 1, 0.2, 2, 0.050),
      make_run("y", "SEMP", 400, "ok", 1, 0.2, 2),
  };
  const std::vector<BenchGroup> groups = summarize(runs);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_DOUBLE_EQ(groups[0].hausdorff, (0.010 + 0.050) / 2);
  EXPECT_DOUBLE_EQ(groups[0].hausdorff_shared, 0.010);
  EXPECT_EQ(groups[0].shared_approx, 1);
  EXPECT_DOUBLE_EQ(groups[1].hausdorff_shared, 0.030);
}

TEST(BenchReport, MarkdownTableHasTheAppendixRowsAndOurFigures) {
  const std::vector<BenchGroup> groups = summarize(synthetic());
  const std::string md = markdown_table(groups);
  // Header: our strategies, then the paper's columns.
  EXPECT_NE(md.find("| Value | \\|F\\| | QQ | TU | paper Q/Q | paper TU |"), std::string::npos)
      << md;
  // QQ at 100: median of {0.5, 0.1, 0.3} is 0.3; TU at 100: median of {0.2,0.4,0.6,0.8} is 0.5.
  char expected[128];
  std::snprintf(expected, sizeof expected, "| Median | 100 | %.3f | %.3f | 0.018 | 0.015 |",
                reference_median({0.5, 0.1, 0.3}), reference_median({0.2, 0.4, 0.6, 0.8}));
  EXPECT_NE(md.find(expected), std::string::npos) << expected << "\n" << md;
  EXPECT_NE(md.find("| Regular | 100 | 40.0 | 80.0 | 99.964 | 100.000 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| Approx | 100 | 60.0 | 80.0 | 100.000 | 100.000 |"), std::string::npos) << md;
  EXPECT_NE(md.find("|  | 2000 | 3.000 | 7.000 | 87.213 | 140.888 |"), std::string::npos) << md;
  for (const char* row : {"| Min | all |", "| Mean |", "| Max |", "| Coverage (%) |",
                          "| Aspect ratio |", "| Hausdorff"})
    EXPECT_NE(md.find(row), std::string::npos) << row;
  // Every table line has the same number of cells.
  std::istringstream lines(md);
  std::size_t cells = 0;
  for (std::string line; std::getline(lines, line);) {
    const std::size_t n = static_cast<std::size_t>(std::count(line.begin(), line.end(), '|')) -
                          static_cast<std::size_t>(std::count(line.begin(), line.end(), '\\'));
    if (cells == 0) cells = n;
    EXPECT_EQ(n, cells) << line;
  }
}

TEST(BenchReport, DocumentHasHeadlineFailuresAndPlots) {
  ReportContext ctx;
  ctx.csv_link = "benchmarks/runs.csv";
  ctx.plots_link = "benchmarks";
  ctx.machine = "test machine";
  ctx.command = "scripts/benchmarks.sh";
  ctx.time_limit = 20;
  const std::string md = markdown_report(synthetic(), ctx);
  EXPECT_NE(md.find("## Headline (2000 faces)"), std::string::npos);
  // QQ at 2,000: median 3 s against the paper's 87.213 s: 29x.
  EXPECT_NE(md.find("87.213 s (**29×** faster)"), std::string::npos) << md;
  // Our TU's median (7 s) over QQ's (3 s).
  EXPECT_NE(md.find("our TU's median is 2.33× QQ's"), std::string::npos) << md;
  EXPECT_NE(md.find("| `d` | 1 of 2 | QQ: timeout at 100 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `e` | 2 of 2 | QQ: budget at 100; TU: crash at 100 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("(benchmarks/median-time.svg)"), std::string::npos);
  EXPECT_NE(md.find("test machine"), std::string::npos);
  EXPECT_NE(md.find(kPaperMachine), std::string::npos);
  EXPECT_NE(md.find("3 of 14 runs failed (1 budget, 1 crash, 1 timeout)"), std::string::npos) << md;
}

TEST(BenchReport, PlotsParseAsXmlAndRender) {
  const fs::path dir = fresh_dir("plots");
  const std::vector<std::string> files = write_plots(summarize(synthetic()), dir.string());
  for (const char* name : {"median-time.svg", "success-approx.svg", "coverage.svg",
                           "aspect-ratio.svg", "hausdorff.svg", "paper-median-time.svg"})
    EXPECT_NE(std::find(files.begin(), files.end(), name), files.end()) << name;
  const std::string time = read_text(dir / "median-time.svg");
  // One line per strategy, a legend entry for each, decade ticks on the log axis.
  const std::regex polyline("<polyline ");
  EXPECT_EQ(std::distance(std::sregex_iterator(time.begin(), time.end(), polyline),
                          std::sregex_iterator()),
            2);
  EXPECT_NE(time.find(">QQ</text>"), std::string::npos);
  EXPECT_NE(time.find(">TU</text>"), std::string::npos);
  for (const char* tick : {">0.1</text>", ">1</text>", ">10</text>"})
    EXPECT_NE(time.find(tick), std::string::npos) << tick;
  EXPECT_NE(time.find(">Number of faces</text>"), std::string::npos);
  for (const std::string& name : files) {
    const fs::path svg = dir / name, png = dir / (name + ".png");
    const int xml = run_tool("xmllint", "--noout " + svg.string());
    if (xml == -1)
      GTEST_SKIP() << "xmllint missing: install libxml2-utils (scripts/install-deps.sh)";
    EXPECT_EQ(xml, 0) << "xmllint rejects " << svg;
    const int rsvg = run_tool("rsvg-convert", "-o " + png.string() + " " + svg.string());
    if (rsvg == -1) GTEST_SKIP() << "rsvg-convert missing: install librsvg2-bin";
    EXPECT_EQ(rsvg, 0) << "rsvg-convert cannot render " << svg;
    EXPECT_GT(fs::file_size(png), 2000u) << png;
  }
  fs::remove_all(dir);
}

TEST(LinePlot, TicksCoverTheRangeInRoundSteps) {
  for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{
           {0, 2000}, {1.13, 2.71}, {0, 100}, {0.004, 0.009}, {5, 5}}) {
    const std::vector<double> t = nice_ticks(lo, hi, 5);
    ASSERT_GE(t.size(), 2u);
    EXPECT_LE(t.front(), lo);
    EXPECT_GE(t.back(), hi);
    const double step = t[1] - t[0];
    for (std::size_t i = 1; i < t.size(); ++i) EXPECT_NEAR(t[i] - t[i - 1], step, step * 1e-9);
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-12));
    EXPECT_TRUE(std::fabs(mantissa - 1) < 1e-9 || std::fabs(mantissa - 2) < 1e-9 ||
                std::fabs(mantissa - 5) < 1e-9)
        << step;
  }
  LinePlot empty;
  empty.series.push_back({"nothing", "red", false, {}});
  const std::string svg = write_line_plot(empty);
  EXPECT_NE(svg.find("nothing (no data)"), std::string::npos);
}

TEST(BenchProgress, LineShowsCountsElapsedAndEta) {
  EXPECT_EQ(progress_line(3, 12, 1, 30, 12),
            "[###.........] 3/12 runs, 1 failed, 0:30 elapsed, ETA 1:30");
  EXPECT_EQ(progress_line(0, 5, 0, 2, 0), "0/5 runs, 0 failed, 0:02 elapsed, ETA ?");
  EXPECT_EQ(progress_line(1, 2, 0, 3700, 0), "1/2 runs, 0 failed, 1:01:40 elapsed, ETA 1:01:40");
  std::ostringstream out;
  BenchProgress plain(2, out, false, 0);
  plain.finished(true, "failed: x");
  plain.tick();
  plain.finished(false, "");
  plain.done();
  EXPECT_NE(out.str().find("failed: x\n"), std::string::npos);
  EXPECT_NE(out.str().find("papernet-bench: 2/2 runs, 1 failed"), std::string::npos) << out.str();
  EXPECT_EQ(out.str().find('\r'), std::string::npos) << "no terminal control in plain mode";
}

TEST(BenchRun, ChildOutcomesBecomeStatuses) {
  const auto record = [](ChildResult child) {
    BenchRun run;
    record_child_result(child, run);
    return run;
  };
  ChildResult ok;
  ok.exit_code = 0;
  ok.seconds = 2.5;
  ok.out =
      "result=complete faces=1000 input_faces=1000 hausdorff=0 overlaps=0 iterations=12 "
      "seconds=1.25 coverage=0.31 aspect_ratio=1.7 check=ok\n";
  const BenchRun complete = record(ok);
  EXPECT_EQ(complete.status, "ok");
  EXPECT_TRUE(complete.has_net());
  EXPECT_DOUBLE_EQ(complete.seconds, 1.25) << "the unfold's own time, not the process's";
  EXPECT_EQ(complete.faces, 1000) << "faces=, not input_faces=";
  EXPECT_DOUBLE_EQ(complete.coverage, 0.31);
  EXPECT_DOUBLE_EQ(complete.aspect_ratio, 1.7);
  EXPECT_EQ(complete.check, "ok");

  ChildResult approx = ok;
  approx.out =
      "result=approximate faces=400 input_faces=1000 hausdorff=0.004 overlaps=0 iterations=9 "
      "seconds=0.5 coverage=0.2 aspect_ratio=2 check=ok\n";
  EXPECT_EQ(record(approx).status, "approx");
  EXPECT_DOUBLE_EQ(record(approx).hausdorff, 0.004);
  EXPECT_TRUE(record(approx).has_net());

  ChildResult timeout;
  timeout.timed_out = true;
  timeout.seconds = 51;
  timeout.err = "working\nstill working\n";
  const BenchRun killed = record(timeout);
  EXPECT_EQ(killed.status, "timeout");
  EXPECT_FALSE(killed.has_net());
  EXPECT_DOUBLE_EQ(killed.seconds, 51);
  EXPECT_EQ(killed.note, "still working");

  ChildResult crash;
  crash.signal = 11;
  EXPECT_EQ(record(crash).status, "crash");
  EXPECT_FALSE(record(crash).has_net());
  ChildResult budget;  // no net in one piece: the part unfolded in grown pieces instead
  budget.exit_code = 0;
  budget.out = "result=complete faces=1000 overlaps=0 seconds=20 pieces=14 grown=1 check=ok\n";
  EXPECT_EQ(record(budget).status, "budget");
  EXPECT_FALSE(record(budget).has_net());
  budget.out = "result=complete faces=1000 overlaps=0 seconds=20 pieces=1 grown=0 check=ok\n";
  EXPECT_EQ(record(budget).status, "ok");
  ChildResult invalid;
  invalid.exit_code = 2;
  EXPECT_EQ(record(invalid).status, "invalid");
  ChildResult check_failed;
  check_failed.exit_code = 1;
  check_failed.out =
      "result=complete faces=10 seconds=1 coverage=0.5 aspect_ratio=1 check=failed\n";
  EXPECT_EQ(record(check_failed).status, "error");
  EXPECT_FALSE(record(check_failed).has_net());
}

TEST(BenchRun, TimeoutKillsTheChild) {
  const ChildResult r = run_child({"/bin/sleep", "20"}, 0.3);
  EXPECT_TRUE(r.timed_out);
  EXPECT_LT(r.seconds, 5);
}

TEST(PaperResults, MatchTheAppendixTable) {
  const fs::path tex = fs::path(papernet::test::shared_data_dir()) / ".." / "seeds" /
                       "progressive-mesh-unfolding.tex";
  if (!fs::exists(tex)) GTEST_SKIP() << "needs ../shared/seeds/progressive-mesh-unfolding.tex";
  const std::string text = read_text(tex);
  const std::size_t from = text.find("\\label{app:Results}");
  ASSERT_NE(from, std::string::npos);
  // Rows "... & |F| & Q/Q & SE/MP & SE/Q & TU \\", in order Median, Mean, Max, Regular, Approx.
  const std::regex row(
      R"(&\s*(\d+)\s*&\s*([\d.]+)\s*&\s*([\d.]+)\s*&\s*([\d.]+)\s*&\s*([\d.]+)\s*\\\\)");
  std::vector<std::vector<double>> rows;
  const std::string table = text.substr(from);
  for (auto it = std::sregex_iterator(table.begin(), table.end(), row);
       it != std::sregex_iterator(); ++it)
    rows.push_back({std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3]),
                    std::stod((*it)[4]), std::stod((*it)[5])});
  ASSERT_EQ(rows.size(), 50u);
  const char* strategies[4] = {"QQ", "SEMP", "SEQ", "TU"};
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int s = 0; s < 4; ++s) {
      const PaperResult* p = paper_result(strategies[s], static_cast<int>(rows[i][0]));
      ASSERT_NE(p, nullptr);
      const double value = i < 10   ? p->median
                           : i < 20 ? p->mean
                           : i < 30 ? p->max
                           : i < 40 ? p->success
                                    : p->success_approx;
      EXPECT_DOUBLE_EQ(value, rows[i][static_cast<std::size_t>(s) + 1])
          << strategies[s] << " row " << i;
    }
}

TEST(BenchCommand, SmallRunWritesCsvReportAndPlots) {
  const fs::path dir = fresh_dir("run");
  fs::create_directories(dir / "bench" / "1000");
  fs::copy_file(fs::path(papernet::test::test_data_dir()) / "sample.obj",
                dir / "bench" / "1000" / "sample.obj");
  // A file that cannot be loaded: an `invalid` run, which must count as a failure.
  std::ofstream(dir / "bench" / "1000" / "broken.obj") << "v 0 0 0\nf 1 2 3\n";
  const std::string cmd = std::string(PAPERNET_BENCH_PROGRAM) + " " + (dir / "bench").string() +
                          " --strategies QQ,TU --time-limit 20 --jobs 2 --csv " +
                          (dir / "runs.csv").string() + " --markdown " + (dir / "doc.md").string() +
                          " --plots " + (dir / "plots").string() + " > " +
                          (dir / "out.txt").string() + " 2> " + (dir / "err.txt").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(dir / "err.txt");
  std::ifstream csv(dir / "runs.csv");
  const std::vector<BenchRun> runs = read_bench_csv(csv);
  ASSERT_EQ(runs.size(), 4u);
  for (const BenchRun& r : runs) {
    SCOPED_TRACE(r.mesh + " " + r.strategy);
    EXPECT_EQ(r.resolution, 1000);
    if (r.mesh == "1000/broken.obj") {
      EXPECT_EQ(r.status, "invalid");
      continue;
    }
    ASSERT_TRUE(r.has_net()) << r.status << ": " << r.note;
    EXPECT_EQ(r.check, "ok");
    EXPECT_GT(r.coverage, 0.01);
    EXPECT_LE(r.coverage, 1.0);
    EXPECT_GE(r.aspect_ratio, 1.0);
  }
  const std::string doc = read_text(dir / "doc.md");
  EXPECT_NE(doc.find("| Approx | 1000 | 50.0 | 50.0 |"), std::string::npos) << doc;
  EXPECT_NE(doc.find("| `broken` | 2 of 2 | QQ: invalid at 1000; TU: invalid at 1000 |"),
            std::string::npos)
      << doc;
  EXPECT_NE(doc.find("](runs.csv)"), std::string::npos);
  EXPECT_NE(doc.find("(plots/median-time.svg)"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "plots" / "coverage.svg"));
  EXPECT_NE(read_text(dir / "err.txt").find("failed: 1000/broken.obj"), std::string::npos);

  // The same report again from the CSV alone.
  const std::string again = std::string(PAPERNET_BENCH_PROGRAM) + " --from-csv " +
                            (dir / "runs.csv").string() + " --markdown " +
                            (dir / "again.md").string() + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(again.c_str()), 0);
  EXPECT_NE(read_text(dir / "again.md").find("| Approx | 1000 | 50.0 | 50.0 |"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace papernet::bench
