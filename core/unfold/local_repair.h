#pragma once

#include <cstddef>
#include <cstdint>

namespace papernet {

/// Budget of Unfolding::repair_locally.
struct LocalRepairOptions {
  /// Largest side of a cut that is moved (tried from 16 faces up, fourfold while nothing helps).
  std::size_t max_side = 256;
  /// Moved-face tests (one grid query each) at most, summed over the whole repair.
  std::size_t max_tests = 100'000;
  /// Moves that do not lower the count (raising it by at most `max_rise` pairs) allowed when no
  /// move lowers it; the links they cut or make are tabu for the next few moves.
  std::size_t max_sideways = 32;
  std::size_t max_rise = 1;
  /// A cut met again in the same round (the pairs' tree paths share links) is not evaluated
  /// again, only its tests are counted; false evaluates it again. The result and the stats are
  /// the same either way (a test compares them).
  bool reuse_cuts = true;
  /// 0: each sideways move is the best one (the lowest count, then the smallest side). Else the
  /// seed of a walk: each sideways move is drawn among all the moves that raise the count by at
  /// most `max_rise` (each gluing is then tested until it raises the count by more than that, and
  /// a cut met again in a round is skipped).
  /// Deterministic for a given seed. The uncollapse tries such walks where the Tabu Unfolder's
  /// runs keep failing on a pair or two (docs/performance.md, "Session 63").
  std::uint64_t seed = 0;
};

/// What Unfolding::repair_locally did.
struct LocalRepairStats {
  std::size_t moves = 0;        ///< moves applied
  std::size_t sideways = 0;     ///< of which did not lower the overlap count
  std::size_t evaluations = 0;  ///< candidate moves evaluated
  std::size_t tests = 0;        ///< moved-face tests
  std::size_t overlaps = 0;     ///< overlapping pairs left
};

}  // namespace papernet
