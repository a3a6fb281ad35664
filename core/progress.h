#pragma once

#include <cstddef>
#include <string>

namespace papernet {

struct Mesh;
struct Net;

/// Where a long computation stands. `faces` is the face count being worked on now (it grows
/// during uncollapse), `input_faces` the count of the mesh handed in.
struct ProgressInfo {
  std::string phase;  // "collapse", "unfold", "uncollapse", "tabs"
  std::size_t faces = 0;
  std::size_t input_faces = 0;
  std::size_t overlaps = 0;
  std::size_t iterations = 0;
  double elapsed_seconds = 0;
  /// The piece being worked on (1-based) and how many there are; 0 when the work is not one
  /// piece's. `faces` and `input_faces` then count all pieces.
  std::size_t piece = 0, pieces = 0;
  /// Of the phase's own work, in [0, 1], where its algorithm can tell (collapses made towards
  /// the target, the tab-room pass's evaluations of its budget); 0 where it cannot.
  double phase_fraction = 0;
  /// Of the whole run, in [0, 1]: never decreasing from one report to the next, exactly 1 at
  /// the end. Set by the pipeline (engine/internal/run_progress.h); algorithms leave it 0.
  double fraction = 0;
};

/// Hook through which long algorithms report progress, hand out intermediate overlap-free
/// nets and learn that they should stop. Algorithms never print; they call this. The default
/// implementation ignores everything and never cancels.
class Progress {
 public:
  virtual ~Progress() = default;
  virtual void report(const ProgressInfo&) {}
  /// An overlap-free net of `mesh` (possibly a coarser approximation of the input).
  virtual void intermediate(const Mesh&, const Net&) {}
  /// Polled often (at least every few milliseconds of work); true stops the algorithm, which
  /// then throws CancelledException.
  virtual bool cancelled() { return false; }
};

}  // namespace papernet
