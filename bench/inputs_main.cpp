// papernet-inputs DIR [--papernet PROGRAM] [--markdown OUT.md] [--time-limit S] [--jobs N]:
// every model file under DIR's folders (gltf/, draco/, classic/, thingi-like/, bad/ of the test
// collection) through `papernet unfold` in a child process, and a table of what became of it:
// a net (its pieces and repairs), a refusal (its reason), or a failure (a crash, a timeout, no
// net). The table of docs/inputs.md; scripts/inputs.sh makes it.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_run.h"

namespace papernet::bench {
namespace {

namespace fs = std::filesystem;

constexpr const char* kUsage =
    "usage: papernet-inputs DIR [--papernet PROGRAM] [--markdown OUT.md] [--time-limit S]\n"
    "                           [--jobs N] [--command TEXT]\n"
    "Runs `papernet unfold FILE -o net.json` (no print: --tab-room-budget 0) on every model\n"
    "file under DIR/<folder>/ (.glb .gltf .drc .obj .off .ply .stl; a folder's .bin and images\n"
    "are read from beside its .gltf) and prints, and writes with --markdown, what became of\n"
    "each: net (pieces, repairs), refused (reason) or failed (crash, timeout, no net).\n";

struct Outcome {
  std::string folder, file;  // file relative to DIR
  std::string kind;          // "net", "refused", "failed"
  std::string detail;        // pieces and repairs, the reason, or what failed
  double seconds = 0;
};

bool is_model(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".glb" || ext == ".gltf" || ext == ".drc" || ext == ".obj" || ext == ".off" ||
         ext == ".ply" || ext == ".stl";
}

std::string last_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  const auto at = text.rfind('\n');
  text = at == std::string::npos ? text : text.substr(at + 1);
  const std::string prefix = "papernet unfold: ";
  if (text.starts_with(prefix)) text = text.substr(prefix.size());
  return text;
}

// What a child run made of one file.
Outcome run_one(const std::string& papernet, const fs::path& dir, const fs::path& file,
                double limit, const std::string& out_json) {
  Outcome o;
  o.folder = fs::relative(file, dir).begin()->string();
  o.file = fs::relative(file, dir).string();
  std::remove(out_json.c_str());
  const ChildResult r = run_child({papernet, "unfold", file.string(), "-o", out_json,
                                   "--time-limit", std::to_string(limit), "--tab-room-budget", "0"},
                                  limit + 60);
  o.seconds = r.seconds;
  if (r.timed_out || r.signal) {
    o.kind = "failed";
    o.detail = r.timed_out ? "timeout" : "crash (signal " + std::to_string(r.signal) + ")";
  } else if (r.exit_code == 2) {
    o.kind = "refused";
    o.detail = last_line(r.err);
    const std::string at = file.string() + ": ";
    if (const auto p = o.detail.find(at); p != std::string::npos)
      o.detail = o.detail.substr(p + at.size());
  } else if (r.exit_code != 0) {
    o.kind = "failed";
    o.detail = "exit " + std::to_string(r.exit_code) + ": " + last_line(r.err);
  } else {
    o.kind = "net";
    std::ifstream in(out_json);
    std::stringstream text;
    text << in.rdbuf();
    const nlohmann::json net = nlohmann::json::parse(text.str(), nullptr, false);
    if (net.is_discarded() || !net.contains("net") || !net.contains("mesh")) {
      o.kind = "failed";
      o.detail = "exit 0 without a net JSON";
      return o;
    }
    // papernet.net/1 (a program from before pieces) has one piece and no repairs.
    const std::size_t pieces = net.contains("pieces") ? net["pieces"].size() : 1;
    std::ostringstream d;
    d << pieces << (pieces == 1 ? " piece" : " pieces") << ", " << net["mesh"]["faces"].size()
      << " faces, " << net["result"].get<std::string>();
    for (const auto& repair : net.value("repairs", nlohmann::json::array()))
      d << "; " << repair["code"].get<std::string>() << " " << repair["count"].get<long>();
    for (const auto& warning : net.value("warnings", nlohmann::json::array()))
      d << "; warning " << warning["code"].get<std::string>() << " "
        << warning["count"].get<long>();
    o.detail = d.str();
  }
  return o;
}

std::string escape(std::string s) {
  for (std::size_t i = 0; (i = s.find('|', i)) != std::string::npos; i += 2) s.replace(i, 1, "\\|");
  return s;
}

}  // namespace

int inputs(int argc, char** argv) {
  std::string dir, papernet, markdown, command;
  double limit = 60;
  int jobs = 2;
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
      } else if (arg == "--papernet") {
        papernet = value();
      } else if (arg == "--markdown") {
        markdown = value();
      } else if (arg == "--command") {
        command = value();
      } else if (arg == "--time-limit") {
        limit = std::stod(value());
      } else if (arg == "--jobs") {
        jobs = std::max(1, std::stoi(value()));
      } else if (!arg.starts_with("-") && dir.empty()) {
        dir = arg;
      } else {
        throw std::invalid_argument("unknown option " + arg);
      }
    }
    if (dir.empty() || !fs::is_directory(dir)) throw std::invalid_argument("no folder DIR");
    if (papernet.empty())
      papernet = (fs::path(self_executable()).parent_path() / "papernet").string();
  } catch (const std::exception& e) {
    std::cerr << "papernet-inputs: " << e.what() << "\n" << kUsage;
    return 1;
  }
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const fs::path relative = fs::relative(entry.path(), dir);
    if (entry.is_regular_file() && is_model(entry.path()) &&
        std::distance(relative.begin(), relative.end()) > 1)  // in a folder of DIR
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  std::vector<Outcome> outcomes(files.size());
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> workers;
  for (int w = 0; w < jobs; ++w)
    workers.emplace_back([&, w] {
      const std::string out_json =
          (fs::temp_directory_path() /
           ("papernet-inputs-" + std::to_string(getpid()) + "-" + std::to_string(w) + ".json"))
              .string();
      for (std::size_t k; (k = next++) < files.size();) {
        outcomes[k] = run_one(papernet, dir, files[k], limit, out_json);
        std::cerr << "[" << k + 1 << "/" << files.size() << "] " << outcomes[k].file << ": "
                  << outcomes[k].kind << "\n";
      }
      std::remove(out_json.c_str());
    });
  for (std::thread& t : workers) t.join();

  // Counts per folder, then every file.
  std::map<std::string, std::map<std::string, int>> counts;
  for (const Outcome& o : outcomes) ++counts[o.folder][o.kind], ++counts["all"][o.kind];
  std::ostringstream md;
  md << "<!-- Generated by `" << (command.empty() ? "papernet-inputs" : command)
     << "`; do not edit by hand. -->\n\n"
     << "| folder | files | net | refused | failed |\n|---|---:|---:|---:|---:|\n";
  for (const auto& entry : counts) {
    const std::string& folder = entry.first;
    if (folder == "all") continue;
    const auto n = [&](const char* k) { return entry.second.count(k) ? entry.second.at(k) : 0; };
    md << "| `" << folder << "/` | " << n("net") + n("refused") + n("failed") << " | " << n("net")
       << " | " << n("refused") << " | " << n("failed") << " |\n";
  }
  const auto& all = counts["all"];
  const auto n = [&](const char* k) { return all.count(k) ? all.at(k) : 0; };
  md << "| all | " << files.size() << " | " << n("net") << " | " << n("refused") << " | "
     << n("failed") << " |\n\n"
     << "| file | result | pieces, faces, repairs / reason | s |\n|---|---|---|---:|\n";
  for (const Outcome& o : outcomes) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.2f", o.seconds);
    md << "| `" << escape(o.file) << "` | " << o.kind << " | " << escape(o.detail) << " | "
       << seconds << " |\n";
  }
  std::cout << md.str();
  if (!markdown.empty()) {
    std::ofstream out(markdown);
    out << md.str();
    if (!out) {
      std::cerr << "papernet-inputs: cannot write " << markdown << "\n";
      return 1;
    }
  }
  return n("failed") == 0 ? 0 : 3;
}

}  // namespace papernet::bench

int main(int argc, char** argv) { return papernet::bench::inputs(argc, argv); }
