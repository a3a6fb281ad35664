#pragma once
// A function run in a child process of its own (fork), so that the peak resident memory the
// benchmarks report is that run's alone: papernet-colour-bench and papernet-scale-bench.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <exception>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>

namespace papernet::bench {

struct ChildRun {
  std::string text;    ///< what the function returned, as the child wrote it back
  double peak_mb = 0;  ///< the child's peak resident memory
  bool ok = false;     ///< the child returned (a throw is written to stderr, and ok is false)
};

/// Runs `run` in a forked child and returns its text through a pipe, with its peak memory.
inline ChildRun in_child(const std::function<std::string()>& run) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    close(fds[0]);
    int code = 0;
    std::string text;
    try {
      text = run();
    } catch (const std::exception& e) {
      std::cerr << "the run failed: " << e.what() << "\n";
      code = 1;
    }
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    text = std::to_string(usage.ru_maxrss / 1024.0) + " " + text;
    if (write(fds[1], text.data(), text.size()) < 0) code = 2;
    _exit(code);
  }
  close(fds[1]);
  std::string text;
  char buf[4096];
  for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;) text.append(buf, n);
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  ChildRun r;
  const std::size_t space = text.find(' ');
  if (space != std::string::npos) {
    r.peak_mb = std::stod(text.substr(0, space));
    r.text = text.substr(space + 1);
  }
  r.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  return r;
}

}  // namespace papernet::bench
