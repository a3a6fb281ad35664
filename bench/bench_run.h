#pragma once
// Running one unfold as an isolated child process, for `papernet bench`.

#include <string>
#include <vector>

#include "bench/bench_report.h"

namespace papernet::bench {

/// How a child run ended.
struct ChildResult {
  int exit_code = -1;      ///< exit status, -1 when killed by a signal or the timeout
  int signal = 0;          ///< the signal that ended it, 0 if none
  bool timed_out = false;  ///< killed after `timeout_seconds`
  double seconds = 0;      ///< wall-clock time
  double cpu_seconds = 0;  ///< user + system time of the child
  std::string out;         ///< what it wrote on stdout
  std::string err;         ///< what it wrote on stderr (last 4 KiB)
};

/// Runs `argv` (argv[0] is the program path) in a child process with no input, collects its
/// output and kills it after `timeout_seconds` (<= 0: no timeout). Never throws for a failing
/// child; throws std::runtime_error only when the child cannot be started.
ChildResult run_child(const std::vector<std::string>& argv, double timeout_seconds);

/// Fills `run` from how a child `papernet unfold` ended: its status (timeout, crash, ok,
/// approx, budget for a net in grown pieces (grown=K > 0: no overlap-free net in one piece),
/// invalid for exit 2, error otherwise), times, the figures of its
/// summary line (faces, overlaps, check, hausdorff, coverage, aspect_ratio) and, for a run that
/// is not "ok", the last line of its stderr as the note. A timeout or crash never has a net.
void record_child_result(const ChildResult& child, BenchRun& run);

/// Path of the running executable (/proc/self/exe).
std::string self_executable();

}  // namespace papernet::bench
