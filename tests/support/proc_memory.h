// A process's memory as /proc reports it, and the check that a server's memory grew by less than
// a bound (not checked under ASan).
#pragma once

#include <gtest/gtest.h>
#include <sys/types.h>

#include <cstddef>
#include <fstream>
#include <iostream>
#include <string>

#include "tests/support/sanitized.h"

namespace papernet::test {

/// A field of /proc/PID/status in kB (VmRSS, VmHWM).
inline std::size_t proc_status_kb(pid_t pid, const std::string& field) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(field + ":", 0) == 0) return std::stoul(line.substr(field.size() + 1));
  ADD_FAILURE() << "no " << field << " in /proc/" << pid << "/status";
  return 0;
}

/// Checks that a server's memory figure (kB) grew by less than `bound_kb`. Under
/// AddressSanitizer (`make sanitize`) the figures measure ASan's allocator, which keeps freed
/// blocks in a quarantine of up to 256 MB and adds redzones, not ours: there the bound is
/// reported as not checked, and the plain build (`make check`) checks it.
inline void expect_memory_growth_below(std::size_t before_kb, std::size_t after_kb,
                                       std::size_t bound_kb, const std::string& what) {
#ifdef PAPERNET_TEST_ASAN
  std::cout << "[ figures  ] ASan build: memory bound (" << bound_kb << " kB, " << what
            << ") not checked, grew " << (after_kb > before_kb ? after_kb - before_kb : 0)
            << " kB\n";
#else
  EXPECT_LT(after_kb, before_kb + bound_kb) << what;
#endif
}

}  // namespace papernet::test
