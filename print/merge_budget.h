#pragma once

#include <cstddef>

namespace papernet {

// The bounds of the merge after the fit search (print/merge.h, MergeBudget), in a header of their
// own: the print's options (print/layout.h) need them, and most of the code includes those, while
// only the fit layout's own files include print/merge.h.

/// Moved-face tests the merge after the fit search spends at most unless a caller says otherwise
/// (PrintOptions::merge_budget, JobOptions::merge_budget; MergeBudget::tests).
inline constexpr std::size_t kDefaultMergeBudget = 480'000;
/// Most tests a caller may give that merge (the same bound as the tab room pass's moves; the time
/// such a budget takes was not measured).
inline constexpr std::size_t kMaxMergeBudget = 100'000'000;

}  // namespace papernet
