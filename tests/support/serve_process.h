// A real `papernet serve` process on a free loopback port, for the end-to-end tests. The HTTP
// helpers they share: serve_http.h.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/files.h"
#include "tests/support/paths.h"
#include "tests/support/postgres.h"

namespace papernet::test {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// One `papernet serve` process with its own data directory.
class Server {
 public:
  explicit Server(std::vector<std::string> flags, fs::path data = {})
      : flags_(with_store_flags(std::move(flags))),
        data_(data.empty()
                  ? fs::temp_directory_path() / ("papernet_serve_" + std::to_string(::getpid()) +
                                                 "_" + std::to_string(counter_++))
                  : data) {
    fs::create_directories(data_);
    start();
  }
  ~Server() {
    stop(SIGKILL);
    if (owns_) fs::remove_all(data_);
  }

  // Port 0: the server binds a free port itself and prints it (no race with other tests).
  void start() {
    port_ = 0;
    const fs::path out = data_ / "stdout.txt";
    fs::remove(out);
    std::vector<std::string> args = {"papernet", "serve",        "--port",       "0",
                                     "--data",   data_.string(), "--access-log", "false"};
    args.insert(args.end(), flags_.begin(), flags_.end());
    // Everything the child needs is made before fork(): the test process has threads, and the
    // child may only make async-signal-safe calls (open, dup2, execv) until it runs the server.
    const std::string binary = papernet_binary();
    const std::string log_path = (data_ / "server.log").string(), out_path = out.string();
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_ = fork();
    if (pid_ == 0) {
      // Close-on-exec: the server keeps the two files as its stderr and stdout only.
      const int err = open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
      const int std_out = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      if (err < 0 || std_out < 0 || dup2(err, STDERR_FILENO) < 0 ||
          dup2(std_out, STDOUT_FILENO) < 0)
        _exit(126);
      execv(binary.c_str(), argv.data());
      _exit(127);
    }
    const std::string prefix = "listening on http://127.0.0.1:";
    for (int i = 0; i < 400; ++i) {
      const std::string text = read_file(out);
      if (const auto at = text.find(prefix);
          port_ == 0 && at != std::string::npos && text.find('\n', at) != std::string::npos)
        port_ = std::stoi(text.substr(at + prefix.size()));
      if (port_ != 0)
        if (auto res = client().Get("/healthz"); res && res->status == 200) return;
      std::this_thread::sleep_for(25ms);
    }
    ADD_FAILURE() << "papernet serve did not come up; log:\n" << log();
  }
  /// Sends `sig` and waits for the process; returns its exit status.
  int stop(int sig) {
    if (pid_ <= 0) return -1;
    kill(pid_, sig);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    return status;
  }
  /// Sends `sig` and waits at most `seconds` for the process (then kills it); returns its exit
  /// status, or -1 when it had to be killed.
  int stop_within(int sig, double seconds) {
    if (pid_ <= 0) return -1;
    kill(pid_, sig);
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    int status = 0;
    while (waitpid(pid_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > end) {
        stop(SIGKILL);
        return -1;
      }
      std::this_thread::sleep_for(10ms);
    }
    pid_ = -1;
    return status;
  }
  void signal(int sig) { kill(pid_, sig); }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(30, 0);
    return c;
  }
  std::string log() const { return read_file(data_ / "server.log"); }
  const fs::path& data() const { return data_; }
  int port() const { return port_; }
  pid_t pid() const { return pid_; }
  void keep_data() { owns_ = false; }

 private:
  static std::vector<std::string> with_store_flags(std::vector<std::string> flags) {
    flags.insert(flags.begin(), server_store_flags().begin(), server_store_flags().end());
    return flags;
  }
  static inline int counter_ = 0;
  std::vector<std::string> flags_;
  fs::path data_;
  int port_ = 0;
  pid_t pid_ = -1;
  bool owns_ = true;
};

}  // namespace papernet::test
