// Runs the papernet program of this build as a user would, for the command-line tests.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

#include "tests/support/paths.h"

namespace papernet::test {

/// Runs `command` through the shell; returns its exit code (-1 when it did not exit) and, when
/// `output` is given, what it wrote to stdout and stderr together.
inline int run_command(const std::string& command, std::string* output = nullptr) {
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  std::string text;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) text.append(buf, n);
  const int status = pclose(p);
  if (output) *output = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Runs `papernet ARGS` through the shell, as run_command.
inline int papernet(const std::string& args, std::string* output = nullptr) {
  return run_command(papernet::test::papernet_binary() + " " + args, output);
}

}  // namespace papernet::test
