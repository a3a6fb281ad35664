#include "bench/bench_run.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace papernet::bench {

namespace {

// Value of `key=` in the unfold command's summary line (space-separated key=value), "" when
// absent.
std::string summary_value(const std::string& out, const std::string& key) {
  std::istringstream words(out.substr(0, out.find('\n')));
  for (std::string word; words >> word;)
    if (word.size() > key.size() && word.compare(0, key.size() + 1, key + "=") == 0)
      return word.substr(key.size() + 1);
  return "";
}

double summary_number(const std::string& out, const std::string& key, double fallback) {
  const std::string v = summary_value(out, key);
  try {
    return v.empty() ? fallback : std::stod(v);
  } catch (const std::exception&) {
    return fallback;
  }
}

}  // namespace

void record_child_result(const ChildResult& r, BenchRun& run) {
  run.seconds = summary_number(r.out, "seconds", r.seconds);
  run.cpu_seconds = r.cpu_seconds;
  run.faces = static_cast<int>(summary_number(r.out, "faces", 0));
  run.overlaps = static_cast<long long>(summary_number(r.out, "overlaps", -1));
  if (!summary_value(r.out, "check").empty()) run.check = summary_value(r.out, "check");
  if (r.timed_out) {
    run.status = "timeout";
    run.seconds = r.seconds;
  } else if (r.signal) {
    run.status = "crash";
    run.note = "signal " + std::to_string(r.signal);
  } else if (r.exit_code == 0 && summary_number(r.out, "grown", 0) > 0) {
    // Unfolded in grown pieces: the unfolder found no overlap-free net in one piece.
    run.status = "budget";
  } else if (r.exit_code == 0) {
    run.status = summary_value(r.out, "result") == "approximate" ? "approx" : "ok";
    if (run.status == "approx") run.hausdorff = summary_number(r.out, "hausdorff", 0);
    run.coverage = summary_number(r.out, "coverage", -1);
    run.aspect_ratio = summary_number(r.out, "aspect_ratio", -1);
  } else if (r.exit_code == 2) {
    run.status = "invalid";
  } else {
    run.status = "error";
  }
  if (run.status != "ok" && run.note.empty()) {
    std::string e = r.err;
    while (!e.empty() && (e.back() == '\n' || e.back() == '\r')) e.pop_back();
    run.note = e.substr(e.rfind('\n') == std::string::npos ? 0 : e.rfind('\n') + 1);
  }
}

std::string self_executable() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) throw std::runtime_error("cannot find the papernet executable");
  return std::string(buf, static_cast<std::size_t>(n));
}

ChildResult run_child(const std::vector<std::string>& argv, double timeout_seconds) {
  int out_pipe[2], err_pipe[2];
  if (pipe2(out_pipe, O_CLOEXEC) != 0 || pipe2(err_pipe, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], 2);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(out_pipe[1]);
  close(err_pipe[1]);
  if (rc != 0) {
    close(out_pipe[0]);
    close(err_pipe[0]);
    throw std::runtime_error(std::string("cannot start ") + argv[0] + ": " + std::strerror(rc));
  }

  ChildResult result;
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
  int open_fds = 2;
  char buf[4096];
  while (open_fds > 0) {
    int wait_ms = 200;
    if (timeout_seconds > 0) {
      const double left = timeout_seconds - elapsed();
      if (left <= 0) {
        kill(pid, SIGKILL);
        result.timed_out = true;
        break;
      }
      wait_ms = static_cast<int>(std::min(200.0, left * 1000) + 1);
    }
    if (poll(fds, 2, wait_ms) < 0 && errno != EINTR) break;
    for (pollfd& p : fds) {
      if (p.fd < 0 || !(p.revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t n = read(p.fd, buf, sizeof buf);
      if (n <= 0) {
        close(p.fd);
        p.fd = -1;
        --open_fds;
        continue;
      }
      std::string& sink = p.fd == out_pipe[0] ? result.out : result.err;
      sink.append(buf, static_cast<std::size_t>(n));
      if (sink.size() > 65536) sink.erase(0, sink.size() - 4096);
    }
  }
  for (pollfd& p : fds)
    if (p.fd >= 0) close(p.fd);
  int status = 0;
  rusage usage{};
  while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  result.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                       1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  result.seconds = elapsed();
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  if (result.err.size() > 4096) result.err.erase(0, result.err.size() - 4096);
  return result;
}

}  // namespace papernet::bench
