// What the service benchmarks share (papernet-store-bench, papernet-stream-bench): a
// `papernet serve` process on a free loopback port, and what /proc says of a process.
#pragma once

#include <httplib.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace papernet::bench {

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// CPU seconds a process used (user + system; with `children`, also its waited-for children's).
inline double cpu_seconds(pid_t pid, bool children = false) {
  const std::string stat = read_file("/proc/" + std::to_string(pid) + "/stat");
  const auto paren = stat.rfind(')');
  if (paren == std::string::npos) return 0;
  std::istringstream fields(stat.substr(paren + 2));
  std::vector<std::string> f{std::istream_iterator<std::string>(fields), {}};
  if (f.size() < 15) return 0;
  // After "pid (comm)": state ppid ... utime (index 11), stime, cutime, cstime.
  double ticks = std::stod(f[11]) + std::stod(f[12]);
  if (children) ticks += std::stod(f[13]) + std::stod(f[14]);
  return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
}

/// One `papernet serve` (program `program`, data in `dir`, the arguments after "serve" in
/// `args`, which must include --port 0) on a free loopback port; SIGTERM when it goes. Its
/// stderr is `dir`/server.log.
class ServeNode {
 public:
  ServeNode(const std::string& program, const std::filesystem::path& dir,
            std::vector<std::string> args)
      : dir_(dir) {
    std::filesystem::create_directories(dir_);
    args.insert(args.begin(), {program, "serve"});
    const std::filesystem::path out = dir_ / "stdout.txt";
    std::cout.flush();  // the child must not print what this process buffered
    std::fflush(nullptr);
    pid_ = fork();
    if (pid_ == 0) {
      if (!freopen((dir_ / "server.log").c_str(), "a", stderr) ||
          !freopen(out.c_str(), "w", stdout))
        _exit(126);
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(argv[0], argv.data());
      _exit(127);
    }
    const std::string prefix = "listening on http://127.0.0.1:";
    for (int i = 0; i < 400 && port_ == 0; ++i) {
      const std::string text = read_file(out);
      if (const auto at = text.find(prefix);
          at != std::string::npos && text.find('\n', at) != std::string::npos)
        port_ = std::stoi(text.substr(at + prefix.size()));
      std::this_thread::sleep_for(std::chrono::milliseconds(25));
    }
    if (port_ == 0) throw std::runtime_error("papernet serve did not start:\n" + log());
  }
  ~ServeNode() {
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
  }
  ServeNode(const ServeNode&) = delete;
  ServeNode& operator=(const ServeNode&) = delete;

  /// A keep-alive client with a 60 s read timeout.
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(60, 0);
    c.set_keep_alive(true);
    c.set_tcp_nodelay(true);
    return c;
  }
  std::string log() const { return read_file(dir_ / "server.log"); }
  pid_t pid() const { return pid_; }
  int port() const { return port_; }

 private:
  std::filesystem::path dir_;
  pid_t pid_ = -1;
  int port_ = 0;
};

}  // namespace papernet::bench
