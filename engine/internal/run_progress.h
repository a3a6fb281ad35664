// Private to engine/: the whole run's progress as one fraction (docs/architecture.md,
// "Progress"), from the phases the steps report.
#pragma once

#include <chrono>
#include <cstddef>

#include "core/progress.h"
#include "engine/pipeline.h"

namespace papernet::engine_detail {

/// Reports `phase` with `done` of it (ProgressInfo::phase_fraction) to `progress`.
void report(Progress& progress, const char* phase, double done);

/// The stages of a run, in order; each has a share of the fraction (run_progress.cpp).
enum class Stage { Prepare, Unfold, Tabs, Print };

/// The stages a run has, known before it starts.
struct RunPlan {
  bool progressive = true;  ///< the unfolder collapses and uncollapses (not TU)
  bool simplify = false;    ///< a collapse before the unfolder (simplify)
  bool tabs = false;        ///< the tab-room pass runs
  bool print = false;       ///< a print document is written (layout, then drawing)
  bool colour = false;      ///< its pages are drawn in colour (known once the model is loaded)
};

/// Forwards the steps' reports to the caller's hook with `ProgressInfo::fraction` set: each stage
/// of the plan has a fixed share of [0, 1] (typical time shares, run_progress.cpp), a piece of a
/// stage a part of it as large as its share of the faces, and within a piece the phases have
/// parts of their own. Where a piece stands in its part: the larger of what its phases report
/// (phase_fraction; the uncollapse's faces) and the clock's share of its time budget. Never
/// lower than the fraction reported before; below 1 until finish(). Cancellation, intermediate
/// nets and outcomes go through unchanged.
class RunProgress : public PipelineProgress {
 public:
  RunProgress(PipelineProgress& to, const RunPlan& plan);
  /// A stage starts, or one piece's part of it: `faces` of `all_faces`, after `faces_before`
  /// (0 of 0: the whole stage), within `seconds` (<= 0: not bounded).
  void start(Stage stage, double seconds = 0, std::size_t faces_before = 0, std::size_t faces = 0,
             std::size_t all_faces = 0);
  void report(const ProgressInfo& info) override;
  /// Whether the print's pages are drawn in colour, known once the model is loaded (RunPlan).
  void set_colour(bool colour) { plan_.colour = colour; }
  /// The last report: phase "write", fraction 1.
  void finish(std::size_t faces, std::size_t input_faces);

  bool cancelled() override { return to_.cancelled(); }
  void intermediate(const Mesh& mesh, const Net& net) override { to_.intermediate(mesh, net); }
  bool wants_intermediates() const override { return to_.wants_intermediates(); }
  void intermediate_outcome(const UnfoldOutcome& outcome) override {
    to_.intermediate_outcome(outcome);
  }

 private:
  using Clock = std::chrono::steady_clock;
  /// Where the current piece stands in its stage's part, in [0, 1].
  double within(const ProgressInfo& info);

  PipelineProgress& to_;
  RunPlan plan_;
  Stage stage_ = Stage::Prepare;
  double from_ = 0, to_share_ = 1;  // the piece's part of its stage
  std::size_t faces_before_ = 0, faces_ = 0;
  std::size_t coarse_faces_ = 0;  // the piece's faces when its uncollapse started (0: not yet)
  double seconds_ = 0;
  Clock::time_point started_ = Clock::now();
  double last_ = 0;
};

}  // namespace papernet::engine_detail
