#include "bench/bench_progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace papernet::bench {

namespace {

std::string clock_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

}  // namespace

std::string progress_line(std::size_t done, std::size_t total, std::size_t failed,
                          double elapsed_seconds, int bar_width) {
  // An ostringstream rather than operator+ chains: gcc 12 warns falsely (-Wrestrict) on those.
  std::ostringstream line;
  if (bar_width > 0) {
    const int filled =
        total ? static_cast<int>(static_cast<double>(bar_width) * static_cast<double>(done) /
                                 static_cast<double>(total))
              : bar_width;
    line << '[' << std::string(static_cast<std::size_t>(filled), '#')
         << std::string(static_cast<std::size_t>(bar_width - filled), '.') << "] ";
  }
  line << done << '/' << total << " runs, " << failed << " failed, " << clock_text(elapsed_seconds)
       << " elapsed, ETA ";
  if (done == 0)
    line << '?';
  else
    line << clock_text(elapsed_seconds / static_cast<double>(done) *
                       static_cast<double>(total - done));
  return line.str();
}

BenchProgress::BenchProgress(std::size_t total, std::ostream& out, bool terminal,
                             double interval_seconds)
    : out_(out),
      total_(total),
      terminal_(terminal),
      interval_(interval_seconds),
      start_(std::chrono::steady_clock::now()) {}

double BenchProgress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void BenchProgress::draw_locked() {
  if (terminal_) {
    out_ << "\r\033[K" << progress_line(done_, total_, failed_, elapsed(), 30) << std::flush;
  } else {
    out_ << "papernet-bench: " << progress_line(done_, total_, failed_, elapsed(), 0) << "\n"
         << std::flush;
    last_line_ = elapsed();
  }
}

void BenchProgress::finished(bool failed, const std::string& message) {
  const std::lock_guard<std::mutex> lock(mutex_);
  ++done_;
  failed_ += failed;
  if (!message.empty()) out_ << (terminal_ ? "\r\033[K" : "") << message << "\n";
  if (terminal_) draw_locked();
}

void BenchProgress::tick() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (terminal_ || elapsed() - last_line_ >= interval_) draw_locked();
}

void BenchProgress::done() {
  const std::lock_guard<std::mutex> lock(mutex_);
  draw_locked();
  if (terminal_) out_ << "\n";
}

}  // namespace papernet::bench
