#pragma once
// The progress display of `papernet bench`: a redrawn bar on a terminal, periodic plain lines
// otherwise (logs, CI).

#include <chrono>
#include <mutex>
#include <ostream>
#include <string>

namespace papernet::bench {

/// "[#####.....] 123/1080 runs, 5 failed, 2:13 elapsed, ETA 10:20" (no bar when bar_width is 0;
/// "ETA ?" before the first run ends). Times as m:ss, or h:mm:ss from an hour on.
std::string progress_line(std::size_t done, std::size_t total, std::size_t failed,
                          double elapsed_seconds, int bar_width);

/// Thread-safe progress of `total` runs written to `out`.
class BenchProgress {
 public:
  /// `terminal`: redraw one line in place; else a plain line every `interval_seconds`.
  BenchProgress(std::size_t total, std::ostream& out, bool terminal, double interval_seconds = 30);

  /// A run ended; `message` (may be empty) is printed on its own line, e.g. for a failure.
  void finished(bool failed, const std::string& message);
  /// Redraws the bar (terminal) or prints a line when the interval has passed. Call about once
  /// a second.
  void tick();
  /// The final line.
  void done();

  double elapsed() const;

 private:
  void draw_locked();
  std::mutex mutex_;
  std::ostream& out_;
  const std::size_t total_;
  std::size_t done_ = 0, failed_ = 0;
  const bool terminal_;
  const double interval_;
  const std::chrono::steady_clock::time_point start_;
  double last_line_ = 0;
};

}  // namespace papernet::bench
