// `papernet bench DIR --strategies TU --time-limit S --jobs N --csv out.csv`: every mesh in
// DIR/<faces>/*.obj unfolded by every strategy, each run in its own `papernet unfold` process
// so that a crash or a hang counts as a failed run and cannot take the benchmark down.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "server/bench_run.h"
#include "server/commands.h"

namespace papernet::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* kUsage =
    "usage: papernet bench DIR [--strategies TU[,QQ,...]] [--time-limit S] [--jobs N]\n"
    "                          [--csv OUT.csv] [--seed N] [--sizes 100,200,...]\n"
    "Unfolds every DIR/<faces>/*.obj with each strategy in a child `papernet unfold` process\n"
    "(killed at the time limit plus a grace period) and prints, per face count, the success\n"
    "rate and the median/mean/max seconds.\n";

struct Run {
  std::string mesh, strategy;
  int faces_dir = 0;  // the folder's face count
  std::string status, check = "-";
  int faces = 0;
  long long overlaps = -1;
  double seconds = 0, cpu_seconds = 0;
  double hausdorff = 0;  // of an approximate result (status "approx")
  std::string note;
};

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::stringstream in(s);
  for (std::string part; std::getline(in, part, sep);)
    if (!part.empty()) parts.push_back(part);
  return parts;
}

// Value of `key=` in the unfold command's summary line, "" when absent.
std::string summary_value(const std::string& out, const std::string& key) {
  const std::size_t at = out.find(key + "=");
  if (at == std::string::npos) return "";
  const std::size_t from = at + key.size() + 1;
  return out.substr(from, out.find_first_of(" \n", from) - from);
}

void execute(Run& run, const std::string& exe, const std::string& file, unsigned long long seed,
             double limit, const std::string& tmp) {
  const ChildResult r =
      run_child({exe, "unfold", file, "--strategy", run.strategy, "-o", tmp, "--seed",
                 std::to_string(seed), "--time-limit", std::to_string(limit)},
                limit + 30 + limit * 0.5);
  std::remove(tmp.c_str());
  run.seconds = r.seconds;
  run.cpu_seconds = r.cpu_seconds;
  if (!summary_value(r.out, "seconds").empty())
    run.seconds = std::stod(summary_value(r.out, "seconds"));
  if (!summary_value(r.out, "faces").empty()) run.faces = std::stoi(summary_value(r.out, "faces"));
  if (!summary_value(r.out, "overlaps").empty())
    run.overlaps = std::stoll(summary_value(r.out, "overlaps"));
  if (!summary_value(r.out, "check").empty()) run.check = summary_value(r.out, "check");
  if (r.timed_out) {
    run.status = "timeout";
    run.seconds = r.seconds;
  } else if (r.signal) {
    run.status = "crash";
    run.note = "signal " + std::to_string(r.signal);
  } else if (r.exit_code == 0) {
    run.status = summary_value(r.out, "result") == "approximate" ? "approx" : "ok";
    if (!summary_value(r.out, "hausdorff").empty())
      run.hausdorff = std::stod(summary_value(r.out, "hausdorff"));
  } else if (r.exit_code == 2) {
    run.status = "invalid";
  } else if (r.exit_code == 3) {
    run.status = "budget";
  } else {
    run.status = "error";
  }
  if (run.status != "ok" && run.note.empty()) {
    std::string e = r.err;
    while (!e.empty() && (e.back() == '\n' || e.back() == '\r')) e.pop_back();
    run.note = e.substr(e.rfind('\n') == std::string::npos ? 0 : e.rfind('\n') + 1);
  }
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int bench(int argc, char** argv) {
  std::string dir, csv;
  std::vector<std::string> strategies{"TU"};
  std::vector<int> sizes;
  double limit = 60;
  int jobs = 1;
  unsigned long long seed = 1;
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
        strategies = split(value(), ',');
      } else if (arg == "--time-limit") {
        limit = std::stod(value());
      } else if (arg == "--jobs") {
        jobs = std::max(1, std::stoi(value()));
      } else if (arg == "--csv") {
        csv = value();
      } else if (arg == "--seed") {
        seed = std::stoull(value());
      } else if (arg == "--sizes") {
        for (const std::string& s : split(value(), ',')) sizes.push_back(std::stoi(s));
      } else if (!arg.empty() && arg[0] == '-') {
        throw std::invalid_argument("unknown option " + arg);
      } else {
        dir = arg;
      }
    }
    if (dir.empty()) throw std::invalid_argument("no folder given");
    if (!fs::is_directory(dir)) throw std::invalid_argument(dir + " is not a folder");
    if (strategies.empty()) throw std::invalid_argument("no strategy given");
  } catch (const std::exception& e) {
    std::cerr << "papernet bench: " << e.what() << "\n" << kUsage;
    return 1;
  }

  // DIR/<faces>/*.obj, by face count then name.
  std::vector<Run> runs;
  std::vector<std::string> files;
  std::vector<std::pair<int, fs::path>> folders;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_directory() || name.empty() ||
        name.find_first_not_of("0123456789") != std::string::npos)
      continue;
    const int faces = std::stoi(name);
    if (sizes.empty() || std::find(sizes.begin(), sizes.end(), faces) != sizes.end())
      folders.push_back({faces, entry.path()});
  }
  std::sort(folders.begin(), folders.end());
  for (const auto& [faces, path] : folders) {
    std::vector<fs::path> meshes;
    for (const auto& entry : fs::directory_iterator(path))
      if (entry.path().extension() == ".obj") meshes.push_back(entry.path());
    std::sort(meshes.begin(), meshes.end());
    for (const fs::path& m : meshes)
      for (const std::string& s : strategies) {
        Run run;
        run.mesh = fs::relative(m, dir).string();
        run.strategy = s;
        run.faces_dir = faces;
        runs.push_back(run);
        files.push_back(m.string());
      }
  }
  if (runs.empty()) {
    std::cerr << "papernet bench: no DIR/<faces>/*.obj meshes in " << dir << "\n";
    return 1;
  }

  std::string exe;
  try {
    exe = self_executable();
  } catch (const std::exception& e) {
    std::cerr << "papernet bench: " << e.what() << "\n";
    return 1;
  }
  std::cerr << "papernet bench: " << runs.size() << " runs, " << jobs << " at a time, " << limit
            << " s each\n";
  std::atomic<std::size_t> next{0};
  std::mutex print;
  std::vector<std::thread> workers;
  for (int w = 0; w < jobs; ++w)
    workers.emplace_back([&, w] {
      const std::string tmp =
          (fs::temp_directory_path() /
           ("papernet-bench-" + std::to_string(getpid()) + "-" + std::to_string(w) + ".json"))
              .string();
      for (std::size_t i; (i = next++) < runs.size();) {
        try {
          execute(runs[i], exe, files[i], seed, limit, tmp);
        } catch (const std::exception& e) {
          runs[i].status = "error";
          runs[i].note = e.what();
        }
        const std::lock_guard<std::mutex> lock(print);
        std::cerr << "[" << i + 1 << "/" << runs.size() << "] " << runs[i].mesh << " "
                  << runs[i].strategy << " " << runs[i].status << " " << std::fixed
                  << std::setprecision(3) << runs[i].seconds << " s\n";
      }
    });
  for (std::thread& t : workers) t.join();

  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "mesh,faces,strategy,seed,status,seconds,cpu_seconds,overlaps,net_check,note,"
           "hausdorff\n";
    for (const Run& r : runs)
      out << csv_field(r.mesh) << "," << (r.faces ? r.faces : r.faces_dir) << "," << r.strategy
          << "," << seed << "," << r.status << "," << r.seconds << "," << r.cpu_seconds << ","
          << r.overlaps << "," << r.check << "," << csv_field(r.note) << "," << r.hausdorff << "\n";
    if (!out) {
      std::cerr << "papernet bench: cannot write " << csv << "\n";
      return 1;
    }
  }

  // Per strategy and face count: success rate; seconds of every run (a failed run counts with
  // the time it took, at least the limit), and of the successful ones.
  std::cout << "seconds: wall-clock of the unfold itself (load to net check); cpu: user+system "
               "time of the whole child process\n"
            << "strategy  faces  runs  success   median    mean     max  med(ok)  med-cpu  "
               "max-cpu\n";
  std::map<std::pair<std::string, int>, std::vector<const Run*>> groups;
  for (const Run& r : runs) groups[{r.strategy, r.faces_dir}].push_back(&r);
  for (const auto& [key, group] : groups) {
    std::vector<double> all, ok, cpu;
    double max_cpu = 0;
    for (const Run* r : group) {
      all.push_back(r->seconds);
      cpu.push_back(r->cpu_seconds);
      max_cpu = std::max(max_cpu, r->cpu_seconds);
      if (r->status == "ok") ok.push_back(r->seconds);
    }
    double sum = 0, max = 0;
    for (double s : all) sum += s, max = std::max(max, s);
    char line[256];
    std::snprintf(line, sizeof line, "%-8s %6d %5zu  %6.1f%% %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f\n",
                  key.first.c_str(), key.second, group.size(),
                  100.0 * static_cast<double>(ok.size()) / static_cast<double>(group.size()),
                  median(all), sum / static_cast<double>(all.size()), max, median(ok), median(cpu),
                  max_cpu);
    std::cout << line;
  }
  // Progressive strategies: approximate results (a net of a coarser mesh) next to complete ones.
  std::cout << "\nstrategy  faces  complete  incl.approx   p95(s)  mean-hausdorff(approx)\n";
  for (const auto& [key, group] : groups) {
    std::vector<double> all;
    std::size_t complete = 0, approx = 0;
    double hausdorff = 0;
    for (const Run* r : group) {
      all.push_back(r->seconds);
      complete += r->status == "ok";
      if (r->status == "approx") ++approx, hausdorff += r->hausdorff;
    }
    std::sort(all.begin(), all.end());
    const double n = static_cast<double>(group.size());
    const double p95 = all[std::min(all.size() - 1, static_cast<std::size_t>(0.95 * n))];
    char line[256];
    std::snprintf(line, sizeof line, "%-8s %6d  %7.1f%%  %10.1f%% %8.3f  %s\n", key.first.c_str(),
                  key.second, 100.0 * static_cast<double>(complete) / n,
                  100.0 * static_cast<double>(complete + approx) / n, p95,
                  approx ? std::to_string(hausdorff / static_cast<double>(approx)).c_str() : "-");
    std::cout << line;
  }
  return 0;
}

}  // namespace papernet::cli
