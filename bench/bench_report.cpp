#include "bench/bench_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <istream>
#include <limits>
#include <map>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "bench/paper_results.h"

namespace papernet::bench {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// Splits CSV text into records of fields (RFC 4180 quoting; newlines inside quotes kept).
std::vector<std::vector<std::string>> parse_csv(std::istream& in) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string field;
  bool quoted = false, any = false;
  for (char c; in.get(c);) {
    any = true;
    if (quoted) {
      if (c != '"') {
        field += c;
      } else if (in.peek() == '"') {
        in.get(c);
        field += '"';
      } else {
        quoted = false;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      record.push_back(std::move(field));
      field.clear();
    } else if (c == '\n') {
      record.push_back(std::move(field));
      field.clear();
      records.push_back(std::move(record));
      record.clear();
      any = false;
    } else if (c != '\r') {
      field += c;
    }
  }
  if (quoted) throw std::runtime_error("CSV ends inside a quoted field");
  if (any) {
    record.push_back(std::move(field));
    records.push_back(std::move(record));
  }
  return records;
}

double mean(const std::vector<double>& v) {
  if (v.empty()) return kNaN;
  double sum = 0;
  for (double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "–";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

}  // namespace

void write_bench_csv(std::ostream& out, const std::vector<BenchRun>& runs) {
  out << "mesh,faces,strategy,seed,status,seconds,cpu_seconds,overlaps,net_check,note,hausdorff,"
         "resolution,coverage,aspect_ratio\n";
  for (const BenchRun& r : runs)
    out << csv_field(r.mesh) << "," << (r.faces ? r.faces : r.resolution) << ","
        << csv_field(r.strategy) << "," << r.seed << "," << r.status << "," << r.seconds << ","
        << r.cpu_seconds << "," << r.overlaps << "," << r.check << "," << csv_field(r.note) << ","
        << r.hausdorff << "," << r.resolution << "," << r.coverage << "," << r.aspect_ratio << "\n";
}

std::vector<BenchRun> read_bench_csv(std::istream& in) {
  const auto records = parse_csv(in);
  if (records.empty()) throw std::runtime_error("empty CSV: no header line");
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < records[0].size(); ++i) column[records[0][i]] = i;
  for (const char* needed : {"mesh", "strategy", "status", "seconds"})
    if (!column.count(needed))
      throw std::runtime_error(std::string("CSV has no column '") + needed + "'");
  std::vector<BenchRun> runs;
  for (std::size_t line = 1; line < records.size(); ++line) {
    const auto& rec = records[line];
    if (rec.size() == 1 && rec[0].empty()) continue;  // blank line
    if (rec.size() != records[0].size())
      throw std::runtime_error("CSV line " + std::to_string(line + 1) + ": " +
                               std::to_string(rec.size()) + " fields, the header has " +
                               std::to_string(records[0].size()));
    const auto text = [&](const char* name) -> std::string {
      const auto it = column.find(name);
      return it == column.end() ? "" : rec[it->second];
    };
    const auto number = [&](const char* name, double fallback) {
      const std::string s = text(name);
      if (s.empty()) return fallback;
      try {
        std::size_t used = 0;
        const double v = std::stod(s, &used);
        if (used != s.size()) throw std::invalid_argument(s);
        return v;
      } catch (const std::exception&) {
        throw std::runtime_error("CSV line " + std::to_string(line + 1) + ": " + name + " '" + s +
                                 "' is not a number");
      }
    };
    BenchRun r;
    r.mesh = text("mesh");
    r.strategy = text("strategy");
    r.status = text("status");
    r.seconds = number("seconds", 0);
    r.cpu_seconds = number("cpu_seconds", 0);
    r.faces = static_cast<int>(number("faces", 0));
    r.seed = static_cast<unsigned long long>(number("seed", 0));
    r.overlaps = static_cast<long long>(number("overlaps", -1));
    r.check = text("net_check").empty() ? "-" : text("net_check");
    r.note = text("note");
    r.hausdorff = number("hausdorff", 0);
    r.coverage = number("coverage", -1);
    r.aspect_ratio = number("aspect_ratio", -1);
    r.resolution = static_cast<int>(number("resolution", 0));
    if (r.resolution == 0) {  // older CSVs: the folder name is the resolution
      const std::string folder = r.mesh.substr(0, r.mesh.find('/'));
      if (!folder.empty() && folder.find_first_not_of("0123456789") == std::string::npos)
        r.resolution = std::stoi(folder);
      else
        r.resolution = r.faces;
    }
    runs.push_back(std::move(r));
  }
  return runs;
}

double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<BenchGroup> summarize(const std::vector<BenchRun>& runs) {
  std::vector<std::string> order;
  std::map<std::pair<std::string, int>, std::vector<const BenchRun*>> by;
  for (const BenchRun& r : runs) {
    if (std::find(order.begin(), order.end(), r.strategy) == order.end())
      order.push_back(r.strategy);
    by[{r.strategy, r.resolution}].push_back(&r);
  }
  // The paper compares approximation quality over the meshes that every progressive strategy
  // approximated ("shared approximative results"); count per mesh (the path names the
  // resolution) how many of those present approximated it.
  const auto progressive = [](const std::string& s) {
    return s == "QQ" || s == "SEMP" || s == "SEQ";
  };
  const auto n_progressive = std::count_if(order.begin(), order.end(), progressive);
  std::map<std::string, long> approximated_by;
  for (const BenchRun& r : runs)
    if (r.status == "approx" && progressive(r.strategy)) ++approximated_by[r.mesh];
  std::vector<BenchGroup> groups;
  for (const std::string& strategy : order)
    for (const auto& [key, members] : by) {
      if (key.first != strategy) continue;
      BenchGroup g;
      g.strategy = strategy;
      g.resolution = key.second;
      std::vector<double> net, all, cpu, coverage, aspect, hausdorff, shared;
      for (const BenchRun* r : members) {
        ++g.runs;
        g.complete += r->complete();
        g.approx += r->status == "approx";
        g.impossible += r->status == "invalid";
        all.push_back(r->seconds);
        cpu.push_back(r->cpu_seconds);
        if (!r->has_net()) continue;
        net.push_back(r->seconds);
        if (r->coverage >= 0) coverage.push_back(r->coverage);
        if (r->aspect_ratio >= 0) aspect.push_back(r->aspect_ratio);
        if (r->status == "approx") hausdorff.push_back(r->hausdorff);
        if (r->status == "approx" && progressive(strategy) &&
            approximated_by[r->mesh] == n_progressive)
          shared.push_back(r->hausdorff);
      }
      g.min = net.empty() ? kNaN : *std::min_element(net.begin(), net.end());
      g.max = net.empty() ? kNaN : *std::max_element(net.begin(), net.end());
      g.median = median(net);
      g.mean = mean(net);
      g.median_all = median(all);
      g.mean_all = mean(all);
      g.max_all = *std::max_element(all.begin(), all.end());
      std::sort(all.begin(), all.end());
      g.p95_all = all[std::min(all.size() - 1, static_cast<std::size_t>(0.95 * all.size()))];
      g.median_cpu = median(cpu);
      g.max_cpu = *std::max_element(cpu.begin(), cpu.end());
      g.coverage = mean(coverage);
      g.aspect_ratio = mean(aspect);
      g.hausdorff = mean(hausdorff);
      g.hausdorff_shared = mean(shared);
      g.shared_approx = static_cast<int>(shared.size());
      groups.push_back(g);
    }
  return groups;
}

std::string text_tables(const std::vector<BenchGroup>& groups) {
  std::ostringstream out;
  char line[256];
  out << "seconds: wall-clock of the unfold itself (load to net check); cpu: user+system time of "
         "the whole child process\n"
      << "strategy  faces  runs  success   median    mean     max  med(net)  med-cpu  max-cpu\n";
  for (const BenchGroup& g : groups) {
    std::snprintf(line, sizeof line, "%-8s %6d %5d  %6.1f%% %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f\n",
                  g.strategy.c_str(), g.resolution, g.runs, g.success(), g.median_all, g.mean_all,
                  g.max_all, g.median, g.median_cpu, g.max_cpu);
    out << line;
  }
  out << "\nstrategy  faces  complete  incl.approx   p95(s)  coverage  aspect  "
         "mean-hausdorff(approx)\n";
  for (const BenchGroup& g : groups) {
    std::snprintf(line, sizeof line, "%-8s %6d  %7.1f%%  %10.1f%% %8.3f  %8s  %6s  %s\n",
                  g.strategy.c_str(), g.resolution, g.success(), g.success_approx(), g.p95_all,
                  fixed(100 * g.coverage, 1).c_str(), fixed(g.aspect_ratio, 2).c_str(),
                  g.approx ? fixed(g.hausdorff, 6).c_str() : "-");
    out << line;
  }
  return out.str();
}

std::string markdown_table(const std::vector<BenchGroup>& groups) {
  std::vector<std::string> strategies;
  std::vector<int> resolutions;
  std::map<std::pair<std::string, int>, const BenchGroup*> at;
  for (const BenchGroup& g : groups) {
    if (std::find(strategies.begin(), strategies.end(), g.strategy) == strategies.end())
      strategies.push_back(g.strategy);
    if (std::find(resolutions.begin(), resolutions.end(), g.resolution) == resolutions.end())
      resolutions.push_back(g.resolution);
    at[{g.strategy, g.resolution}] = &g;
  }
  std::sort(resolutions.begin(), resolutions.end());
  std::vector<std::string> paper;  // the paper's columns, for strategies it has
  for (const std::string& s : strategies)
    if (paper_result(s, 2000)) paper.push_back(s);

  std::ostringstream out;
  out << "| Value | \\|F\\| |";
  for (const std::string& s : strategies) out << " " << s << " |";
  for (const std::string& s : paper) out << " paper " << paper_strategy_name(s) << " |";
  out << "\n|---|---:|";
  for (std::size_t i = 0; i < strategies.size() + paper.size(); ++i) out << "---:|";
  out << "\n";
  const auto section = [&](const std::string& title) {
    out << "| **" << title << "** | |";
    for (std::size_t i = 0; i < strategies.size() + paper.size(); ++i) out << " |";
    out << "\n";
  };
  // One row per resolution: our figure per strategy, then the paper's (NaN = not in the paper).
  const auto rows = [&](const std::string& name, auto ours, auto theirs, int decimals) {
    for (std::size_t i = 0; i < resolutions.size(); ++i) {
      out << "| " << (i == 0 ? name : "") << " | " << resolutions[i] << " |";
      for (const std::string& s : strategies) {
        const auto it = at.find({s, resolutions[i]});
        out << " " << (it == at.end() ? "–" : fixed(ours(*it->second), decimals)) << " |";
      }
      for (const std::string& s : paper) {
        const PaperResult* p = paper_result(s, resolutions[i]);
        out << " " << (p ? fixed(theirs(*p), 3) : "–") << " |";
      }
      out << "\n";
    }
  };
  const auto none = [](const PaperResult&) { return kNaN; };
  section("Runs");
  rows(
      "Runs", [](const BenchGroup& g) { return g.runs; }, none, 0);
  section("Timings (s) of runs that wrote a net");
  out << "| Min | all |";
  for (const std::string& s : strategies) {
    double m = kNaN;
    for (const BenchGroup& g : groups)
      if (g.strategy == s && std::isfinite(g.min))
        m = std::isfinite(m) ? std::min(m, g.min) : g.min;
    out << " " << fixed(m, 3) << " |";
  }
  for (std::size_t i = 0; i < paper.size(); ++i) out << " 0.000 |";
  out << "\n";
  rows(
      "Min", [](const BenchGroup& g) { return g.min; }, none, 3);
  rows(
      "Median", [](const BenchGroup& g) { return g.median; },
      [](const PaperResult& p) { return p.median; }, 3);
  rows(
      "Mean", [](const BenchGroup& g) { return g.mean; },
      [](const PaperResult& p) { return p.mean; }, 3);
  rows(
      "Max", [](const BenchGroup& g) { return g.max; }, [](const PaperResult& p) { return p.max; },
      3);
  section("Success rates (%)");
  rows(
      "Regular", [](const BenchGroup& g) { return g.success(); },
      [](const PaperResult& p) { return p.success; }, 1);
  rows(
      "Approx", [](const BenchGroup& g) { return g.success_approx(); },
      [](const PaperResult& p) { return p.success_approx; }, 1);
  if (std::any_of(groups.begin(), groups.end(), [](const BenchGroup& g) { return g.impossible; })) {
    rows(
        "Inputs refused as impossible (exit 2)", [](const BenchGroup& g) { return g.impossible; },
        none, 0);
    rows(
        "Regular, of the inputs not refused (where any were)",
        [](const BenchGroup& g) { return g.impossible ? g.success_possible() : kNaN; }, none, 1);
  }
  section("Nets (means over runs that wrote a net)");
  rows(
      "Coverage (%)", [](const BenchGroup& g) { return 100 * g.coverage; }, none, 1);
  rows(
      "Aspect ratio", [](const BenchGroup& g) { return g.aspect_ratio; }, none, 2);
  rows(
      "Hausdorff (% of diagonal, approximations)",
      [](const BenchGroup& g) { return g.approx ? 100 * g.hausdorff : kNaN; }, none, 3);
  rows(
      "Hausdorff (%), shared approximations",
      [](const BenchGroup& g) { return 100 * g.hausdorff_shared; }, none, 3);
  rows(
      "Shared approximations",
      [](const BenchGroup& g) { return g.shared_approx ? g.shared_approx : kNaN; }, none, 0);
  return out.str();
}

std::string describe_machine() {
  std::string cpu, os;
  double ram_gb = 0;
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  std::ifstream meminfo("/proc/meminfo");
  for (std::string key; meminfo >> key;) {
    double kb = 0;
    meminfo >> kb;
    if (key == "MemTotal:") {
      ram_gb = kb / 1024 / 1024;
      break;
    }
    meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  std::ifstream release("/etc/os-release");
  for (std::string line; std::getline(release, line);)
    if (line.rfind("PRETTY_NAME=", 0) == 0) {
      os = line.substr(12);
      os.erase(std::remove(os.begin(), os.end(), '"'), os.end());
    }
  std::ostringstream out;
  out << (cpu.empty() ? "unknown CPU" : cpu) << ", " << std::thread::hardware_concurrency()
      << " logical CPUs, " << fixed(ram_gb, 0) << " GB RAM, " << (os.empty() ? "Linux" : os);
  return out.str();
}

}  // namespace papernet::bench
