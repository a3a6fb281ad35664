#pragma once
// Which sanitizer the test is built with (make sanitize): tests that would measure the speed of
// a sanitized build rather than its correctness keep their work smaller there.

#include <algorithm>
#include <cstddef>
#include <string>

#include "api/options.h"

#if defined(__SANITIZE_ADDRESS__)
#define PAPERNET_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PAPERNET_TEST_ASAN 1
#endif
#endif

#if defined(PAPERNET_TEST_ASAN) || defined(__SANITIZE_THREAD__)
#define PAPERNET_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define PAPERNET_TEST_SANITIZED 1
#endif
#endif

namespace papernet::test {

// Searches run 10-20 times slower sanitized: there, the jobs of tests that are not about a
// search give it less work through the job's own options, so that a job takes seconds, not
// minutes (0: no limit, the defaults).
// - The pass that makes room for tabs (JobOptions::tab_room_budget): at most a tenth of its
//   default budget (sample.obj's TU net keeps 12 tabs to each strip).
// - The merge of pieces after the fit search (JobOptions::merge_budget), two thirds of a default
//   print of the Duck (1.8 s without it, 3.8 s with it, Release): an eighth, which still merges
//   (the Duck 27 pieces without the merge, 22 with this budget, 17 with the default).
#ifdef PAPERNET_TEST_SANITIZED
inline constexpr std::size_t kLightTabRoomBudget = 10'000;
inline constexpr std::size_t kLightMergeBudget = 60'000;
#else
inline constexpr std::size_t kLightTabRoomBudget = 0;
inline constexpr std::size_t kLightMergeBudget = 0;
#endif

/// `budget`, at most `light` unless that is 0.
constexpr std::size_t at_most(std::size_t budget, std::size_t light) {
  return light == 0 ? budget : std::min(budget, light);
}

/// The budgets for a job a test runs itself.
constexpr std::size_t light_tab_room(std::size_t budget) {
  return at_most(budget, kLightTabRoomBudget);
}
constexpr std::size_t light_merge(std::size_t budget) { return at_most(budget, kLightMergeBudget); }

/// Both budgets of a job a test runs itself, lightened.
inline void lighten(JobOptions& options) {
  options.tab_room_budget = light_tab_room(options.tab_room_budget);
  options.merge_budget = light_merge(options.merge_budget);
}

/// `&name=light` to append to a service job's query, or a command line's ` --flag light`
/// (empty when `light` is 0).
inline std::string light_option(const std::string& prefix, std::size_t light) {
  return light == 0 ? std::string() : prefix + std::to_string(light);
}

/// Both for a service job: query options to append (empty when not sanitized).
inline const std::string kLightQuery = light_option("&tab_room_budget=", kLightTabRoomBudget) +
                                       light_option("&merge_budget=", kLightMergeBudget);
/// The merge's for a command line: a flag to append (empty when not sanitized).
inline const std::string kLightMergeFlag = light_option(" --merge-budget ", kLightMergeBudget);

}  // namespace papernet::test
