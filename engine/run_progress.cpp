// The whole run's progress as one fraction: each stage's share, each phase's part of its stage.
#include "engine/internal/run_progress.h"

#include <algorithm>
#include <array>
#include <string>

namespace papernet::engine_detail {

void report(Progress& progress, const char* phase, double done) {
  ProgressInfo info;
  info.phase = phase;
  info.phase_fraction = done;
  progress.report(info);
}

namespace {

// The stages' shares of a run, from their time shares at the defaults (A4, 200 mm, tabs auto,
// colour auto; the net JSON and a PDF or the pages' SVG) on the 8 models of tests/data and the 27
// of ../shared/data/bench/1000, means of each run's shares (docs/architecture.md, "Progress"):
// loading 1 %, the unfolder 20 %, the tab-room pass 18 % (none to 70 %), the print 60-62 %.
// Without the pass or the print, the others share what is left in the same proportions.
constexpr double kPrepareShare = 0.02;
constexpr double kUnfoldShare = 0.18;
constexpr double kTabsShare = 0.19;
constexpr double kPrintShare = 0.61;
// Only the net JSON (and GLB, OBJ) to write: a few milliseconds.
constexpr double kWriteOnlyShare = 0.01;

// Parts of a stage: loading, of preparing (repair and validation take the rest); the layout
// (cutting to fit, tabs, strips, labels, nesting), of the print (the drawing takes the rest):
// 90-94 % of it in line art, 26-29 % with colour, whose pages' images are most of the print
// (the same runs).
constexpr double kLoadPart = 0.5;
constexpr double kLayoutPart = 0.9;
constexpr double kColourLayoutPart = 0.3;
// Parts of a progressive unfolder's work: the collapse, the coarse mesh's unfolding, then the
// uncollapse; of a Tabu Unfolder's with simplify: the collapse, then the unfolding.
constexpr double kCollapsePart = 0.15, kCoarsePart = 0.15;
constexpr double kSimplifyPart = 0.3;

// Reported before the end: 1 means finished.
constexpr double kBeforeEnd = 0.999;

struct Band {
  double from = 0, to = 1;
};

Band part(double from, double to) { return {from, to}; }

}  // namespace

RunProgress::RunProgress(PipelineProgress& to, const RunPlan& plan) : to_(to), plan_(plan) {}

void RunProgress::start(Stage stage, double seconds, std::size_t faces_before, std::size_t faces,
                        std::size_t all_faces) {
  stage_ = stage;
  seconds_ = seconds;
  started_ = Clock::now();
  faces_before_ = faces_before;
  faces_ = faces;
  coarse_faces_ = 0;
  from_ = all_faces > 0 ? double(faces_before) / double(all_faces) : 0;
  to_share_ = all_faces > 0 ? double(faces_before + faces) / double(all_faces) : 1;
}

double RunProgress::within(const ProgressInfo& info) {
  Band band;
  double done = info.phase_fraction;
  const std::string& phase = info.phase;
  switch (stage_) {
    case Stage::Prepare:
      band = phase == "load" ? part(0, kLoadPart) : part(kLoadPart, 1);
      break;
    case Stage::Unfold:
      if (!plan_.progressive) {
        const double collapse = plan_.simplify ? kSimplifyPart : 0;
        band = phase == "collapse" ? part(0, collapse) : part(collapse, 1);
      } else if (phase == "collapse") {
        band = part(0, kCollapsePart);
      } else if (phase == "unfold") {
        band = part(kCollapsePart, kCollapsePart + kCoarsePart);
      } else {  // uncollapse: faces added of those to add
        band = part(kCollapsePart + kCoarsePart, 1);
        const std::size_t faces = info.faces > faces_before_ ? info.faces - faces_before_ : 0;
        if (coarse_faces_ == 0) coarse_faces_ = std::max<std::size_t>(faces, 1);
        if (faces_ > coarse_faces_ && faces > coarse_faces_)
          done = double(faces - coarse_faces_) / double(faces_ - coarse_faces_);
      }
      break;
    case Stage::Tabs:
      break;
    case Stage::Print:
      if (plan_.print) {
        const double layout = plan_.colour ? kColourLayoutPart : kLayoutPart;
        band = phase == "layout" ? part(0, layout) : part(layout, 1);
      }
      break;
  }
  double at = band.from + (band.to - band.from) * std::clamp(done, 0.0, 1.0);
  if (seconds_ > 0)
    at = std::max(at, std::chrono::duration<double>(Clock::now() - started_).count() / seconds_);
  return std::clamp(at, 0.0, 1.0);
}

void RunProgress::report(const ProgressInfo& info) {
  const std::array<double, 4> shares = {kPrepareShare, kUnfoldShare, plan_.tabs ? kTabsShare : 0,
                                        plan_.print ? kPrintShare : kWriteOnlyShare};
  double total = 0, before = 0;
  for (std::size_t s = 0; s < shares.size(); ++s) {
    total += shares[s];
    if (s < static_cast<std::size_t>(stage_)) before += shares[s];
  }
  const double share = shares[static_cast<std::size_t>(stage_)];
  const double in_stage = from_ + (to_share_ - from_) * within(info);
  last_ = std::max(last_, std::min(kBeforeEnd, (before + share * in_stage) / total));
  ProgressInfo out = info;
  out.fraction = last_;
  to_.report(out);
}

void RunProgress::finish(std::size_t faces, std::size_t input_faces) {
  ProgressInfo info;
  info.phase = "write";
  info.faces = faces;
  info.input_faces = input_faces;
  info.phase_fraction = 1;
  info.fraction = last_ = 1;
  to_.report(info);
}

}  // namespace papernet::engine_detail
