// Internal to the tab clearance pass (core/tabs/tab_clearance*.cpp): its progress reports. Not
// part of the public API.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>

#include "core/progress.h"

namespace papernet::tab_clearance_detail {

/// The caller's hook for the whole pass: reports phase "tabs" with the candidate moves evaluated
/// so far (`iterations`) and the share of the pass done (`phase_fraction`): the larger of the
/// evaluations' share of the pass's budget and the clock's of its time limit. At most every
/// kInterval; cancellation as the caller's.
class PassProgress {
 public:
  /// `budget`: candidate moves of both rounds; `seconds`: the time limit (<= 0: none); `faces`:
  /// of the mesh.
  PassProgress(Progress& to, std::size_t budget, double seconds, std::size_t faces)
      : to_(to),
        budget_(budget),
        seconds_(seconds),
        faces_(faces),
        start_(Clock::now()),
        last_(start_) {}
  bool cancelled() { return to_.cancelled(); }
  /// `evaluations` of the pass so far (both rounds and kicks counted).
  void at(std::size_t evaluations) {
    const auto now = Clock::now();
    if (now - last_ < kInterval) return;
    last_ = now;
    report(evaluations, now);
  }
  /// The last report: the pass is over.
  void done(std::size_t evaluations) { report(evaluations, Clock::now(), 1.0); }

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr auto kInterval = std::chrono::milliseconds(50);
  void report(std::size_t evaluations, Clock::time_point now, double at_least = 0) {
    ProgressInfo info;
    info.phase = "tabs";
    info.faces = info.input_faces = faces_;
    info.iterations = evaluations;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    info.elapsed_seconds = elapsed;
    double share = budget_ > 0 ? double(evaluations) / double(budget_) : 0;
    if (seconds_ > 0) share = std::max(share, elapsed / seconds_);
    info.phase_fraction = std::clamp(std::max(share, at_least), 0.0, 1.0);
    to_.report(info);
  }
  Progress& to_;
  std::size_t budget_;
  double seconds_;
  std::size_t faces_;
  Clock::time_point start_, last_;
};

}  // namespace papernet::tab_clearance_detail
