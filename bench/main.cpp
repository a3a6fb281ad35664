// `papernet-bench DIR --strategies TU --time-limit S --jobs N --csv out.csv`: every mesh in
// DIR/<faces>/*.obj unfolded by every strategy, each run in its own `papernet unfold` process
// so that a crash or a hang counts as a failed run and cannot take the benchmark down.
// `--markdown FILE` and `--plots DIR` write the report (bench_report.h), also from an earlier
// run's CSV with `--from-csv FILE`.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_progress.h"
#include "bench/bench_report.h"
#include "bench/bench_run.h"

namespace papernet::bench {

namespace {

namespace fs = std::filesystem;

constexpr const char* kUsage =
    "usage: papernet-bench DIR [--strategies TU[,QQ,...]] [--time-limit S] [--jobs N]\n"
    "                          [--csv OUT.csv] [--seed N] [--sizes 100,200,...]\n"
    "                          [--markdown OUT.md] [--plots DIR] [--machine TEXT]\n"
    "                          [--source TEXT] [--command TEXT] [--note TEXT]\n"
    "                          [--papernet PROGRAM]\n"
    "       papernet-bench --from-csv RUNS.csv [--markdown OUT.md] [--plots DIR] ...\n"
    "Unfolds every DIR/<faces>/*.obj with each strategy in a child `papernet unfold` process\n"
    "(killed at the time limit, default 20 s, plus a grace period; a crash or timeout is a\n"
    "failed run) and prints, per face count, the success rate and the median/mean/max seconds.\n"
    "--csv writes every run; --markdown the report (the paper's Appendix C table, headline\n"
    "ratios, failures per mesh); --plots SVG plots against face count. --from-csv makes the\n"
    "report from an earlier run's CSV without running anything (--time-limit and --jobs then\n"
    "describe that run). --machine/--source/--command fill the report's setup (the machine is\n"
    "detected when not given); --note adds a remark at its top. --papernet names the program\n"
    "that unfolds (default: the papernet beside this one).\n";

struct Options {
  std::string dir, csv, from_csv, markdown, plots, machine, source, command, note, papernet;
  std::vector<std::string> strategies{"TU"};
  std::vector<int> sizes;
  double limit = 20;
  int jobs = 1;
  bool limit_given = false, jobs_given = false;
  unsigned long long seed = 1;
};

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::stringstream in(s);
  for (std::string part; std::getline(in, part, sep);)
    if (!part.empty()) parts.push_back(part);
  return parts;
}

void execute(BenchRun& run, const std::string& exe, const std::string& file, double limit,
             const std::string& tmp) {
  const ChildResult r =
      // The unfolder alone, on every face of the mesh: no collapse to a buildable detail and no
      // pass that changes the cuts for glue tabs (a print's concerns).
      run_child({exe, "unfold", file, "--strategy", run.strategy, "-o", tmp, "--seed",
                 std::to_string(run.seed), "--time-limit", std::to_string(limit), "--detail",
                 "full", "--tab-room-budget", "0"},
                limit + 30 + limit * 0.5);
  std::remove(tmp.c_str());
  record_child_result(r, run);
}

// DIR/<faces>/*.obj, by face count then name, times every strategy.
std::vector<BenchRun> plan_runs(const Options& o, std::vector<std::string>& files) {
  std::vector<std::pair<int, fs::path>> folders;
  for (const auto& entry : fs::directory_iterator(o.dir)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_directory() || name.empty() ||
        name.find_first_not_of("0123456789") != std::string::npos || name.size() > 9)
      continue;
    const int faces = std::stoi(name);
    if (o.sizes.empty() || std::find(o.sizes.begin(), o.sizes.end(), faces) != o.sizes.end())
      folders.push_back({faces, entry.path()});
  }
  std::sort(folders.begin(), folders.end());
  std::vector<BenchRun> runs;
  for (const auto& [faces, path] : folders) {
    std::vector<fs::path> meshes;
    for (const auto& entry : fs::directory_iterator(path))
      if (entry.path().extension() == ".obj") meshes.push_back(entry.path());
    std::sort(meshes.begin(), meshes.end());
    for (const fs::path& m : meshes)
      for (const std::string& s : o.strategies) {
        BenchRun run;
        run.mesh = fs::relative(m, o.dir).string();
        run.strategy = s;
        run.resolution = faces;
        run.seed = o.seed;
        runs.push_back(run);
        files.push_back(m.string());
      }
  }
  return runs;
}

// Runs them all, `jobs` at a time, in a shuffled order so that the ETA is not biased by the
// small meshes coming first. Results land at their index (the CSV stays sorted).
void run_all(std::vector<BenchRun>& runs, const std::vector<std::string>& files, const Options& o,
             const std::string& exe, BenchProgress& progress) {
  std::vector<std::size_t> order(runs.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(12345));
  std::atomic<std::size_t> next{0}, finished{0};
  std::mutex mutex;
  std::condition_variable wake;
  std::vector<std::thread> workers;
  for (int w = 0; w < o.jobs; ++w)
    workers.emplace_back([&, w] {
      const std::string tmp =
          (fs::temp_directory_path() /
           ("papernet-bench-" + std::to_string(getpid()) + "-" + std::to_string(w) + ".json"))
              .string();
      for (std::size_t k; (k = next++) < order.size();) {
        BenchRun& run = runs[order[k]];
        try {
          execute(run, exe, files[order[k]], o.limit, tmp);
        } catch (const std::exception& e) {
          run.status = "error";
          run.note = e.what();
        }
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.1f", run.seconds);
        progress.finished(!run.has_net(), run.has_net()
                                              ? ""
                                              : "failed: " + run.mesh + " " + run.strategy + " " +
                                                    run.status + " after " + seconds + " s");
        ++finished;
        wake.notify_one();
      }
    });
  {
    std::unique_lock<std::mutex> lock(mutex);
    while (finished < runs.size()) {
      wake.wait_for(lock, std::chrono::seconds(1));
      progress.tick();
    }
  }
  for (std::thread& t : workers) t.join();
  progress.done();
}

bool write_reports(const std::vector<BenchRun>& runs, const Options& o, double elapsed) {
  try {
    const std::vector<BenchGroup> groups = summarize(runs);
    std::cout << text_tables(groups);
    if (!o.plots.empty()) {
      const std::vector<std::string> files = write_plots(groups, o.plots);
      std::cerr << "papernet-bench: wrote " << files.size() << " plots to " << o.plots << "\n";
    }
    if (!o.markdown.empty()) {
      const fs::path doc_dir = fs::absolute(o.markdown).parent_path();
      ReportContext ctx;
      const std::string csv = o.from_csv.empty() ? o.csv : o.from_csv;
      if (!csv.empty()) ctx.csv_link = fs::relative(fs::absolute(csv), doc_dir).string();
      if (!o.plots.empty()) ctx.plots_link = fs::relative(fs::absolute(o.plots), doc_dir).string();
      ctx.machine = o.machine;
      ctx.source = o.source;
      ctx.command = o.command;
      ctx.note = o.note;
      // With --from-csv, --time-limit and --jobs describe the run that wrote the CSV.
      ctx.time_limit = o.from_csv.empty() || o.limit_given ? o.limit : 0;
      ctx.jobs = o.from_csv.empty() || o.jobs_given ? o.jobs : 0;
      ctx.elapsed = elapsed;
      std::ofstream out(o.markdown);
      out << markdown_report(runs, ctx);
      if (!out) throw std::runtime_error("cannot write " + o.markdown);
      std::cerr << "papernet-bench: wrote " << o.markdown << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "papernet-bench: " << e.what() << "\n";
    return false;
  }
  return true;
}

}  // namespace

int run(int argc, char** argv) {
  Options o;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      const auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
        return argv[++i];
      };
      if (arg == "--help" || arg == "-h") {
        std::cout << kUsage;
        return 0;
      } else if (arg == "--strategies") {
        o.strategies = split(value(), ',');
      } else if (arg == "--time-limit") {
        o.limit = std::stod(value());
        if (!(o.limit > 0)) throw std::invalid_argument("--time-limit must be > 0");
        o.limit_given = true;
      } else if (arg == "--jobs") {
        o.jobs = std::max(1, std::stoi(value()));
        o.jobs_given = true;
      } else if (arg == "--csv") {
        o.csv = value();
      } else if (arg == "--from-csv") {
        o.from_csv = value();
      } else if (arg == "--markdown") {
        o.markdown = value();
      } else if (arg == "--plots") {
        o.plots = value();
      } else if (arg == "--machine") {
        o.machine = value();
      } else if (arg == "--source") {
        o.source = value();
      } else if (arg == "--command") {
        o.command = value();
      } else if (arg == "--papernet") {
        o.papernet = value();
      } else if (arg == "--note") {
        o.note = value();
      } else if (arg == "--seed") {
        o.seed = std::stoull(value());
      } else if (arg == "--sizes") {
        for (const std::string& s : split(value(), ',')) o.sizes.push_back(std::stoi(s));
      } else if (!arg.empty() && arg[0] == '-') {
        throw std::invalid_argument("unknown option " + arg);
      } else {
        o.dir = arg;
      }
    }
    if (!o.from_csv.empty()) {
      if (!o.dir.empty()) throw std::invalid_argument("--from-csv makes a report only: no DIR");
    } else {
      if (o.dir.empty()) throw std::invalid_argument("no folder given");
      if (!fs::is_directory(o.dir)) throw std::invalid_argument(o.dir + " is not a folder");
      if (o.strategies.empty()) throw std::invalid_argument("no strategy given");
    }
  } catch (const std::exception& e) {
    std::cerr << "papernet-bench: " << e.what() << "\n" << kUsage;
    return 1;
  }

  if (!o.from_csv.empty()) {
    std::ifstream in(o.from_csv, std::ios::binary);
    if (!in) {
      std::cerr << "papernet-bench: cannot read " << o.from_csv << "\n";
      return 1;
    }
    try {
      return write_reports(read_bench_csv(in), o, 0) ? 0 : 1;
    } catch (const std::exception& e) {
      std::cerr << "papernet-bench: " << o.from_csv << ": " << e.what() << "\n";
      return 1;
    }
  }

  std::vector<std::string> files;
  std::vector<BenchRun> runs = plan_runs(o, files);
  if (runs.empty()) {
    std::cerr << "papernet-bench: no DIR/<faces>/*.obj meshes in " << o.dir << "\n";
    return 1;
  }
  std::string exe = o.papernet;
  try {
    if (exe.empty()) exe = (fs::path(self_executable()).parent_path() / "papernet").string();
  } catch (const std::exception& e) {
    std::cerr << "papernet-bench: " << e.what() << "\n";
    return 1;
  }
  if (access(exe.c_str(), X_OK) != 0) {
    std::cerr << "papernet-bench: cannot run " << exe << " (--papernet names the program)\n";
    return 1;
  }
  std::cerr << "papernet-bench: " << runs.size() << " runs, " << o.jobs << " at a time, " << o.limit
            << " s each\n";
  BenchProgress progress(runs.size(), std::cerr, isatty(STDERR_FILENO) != 0);
  run_all(runs, files, o, exe, progress);

  if (!o.csv.empty()) {
    std::ofstream out(o.csv);
    write_bench_csv(out, runs);
    if (!out) {
      std::cerr << "papernet-bench: cannot write " << o.csv << "\n";
      return 1;
    }
  }
  return write_reports(runs, o, progress.elapsed()) ? 0 : 1;
}

}  // namespace papernet::bench

int main(int argc, char** argv) { return papernet::bench::run(argc, argv); }
