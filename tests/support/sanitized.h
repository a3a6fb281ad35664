#pragma once
// Which sanitizer the test is built with (make sanitize): tests that would measure the speed of
// a sanitized build rather than its correctness keep their work smaller there.

#include <algorithm>
#include <cstddef>
#include <string>

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

// The tab room pass runs 10-20 times slower sanitized: there, the jobs of tests that are not
// about the pass give it at most a tenth of its default budget (JobOptions::tab_room_budget), so
// that a job takes seconds, not minutes (sample.obj's TU net keeps 12 tabs to each strip).
#ifdef PAPERNET_TEST_SANITIZED
inline constexpr std::size_t kLightTabRoomBudget = 10'000;
#else
inline constexpr std::size_t kLightTabRoomBudget = 0;  // no limit
#endif

/// The budget for a job a test runs itself: `budget`, at most kLightTabRoomBudget sanitized.
constexpr std::size_t light_tab_room(std::size_t budget) {
  return kLightTabRoomBudget == 0 ? budget : std::min(budget, kLightTabRoomBudget);
}

/// The same for a service job: a query option to append (empty when not sanitized).
inline const std::string kTabRoomQuery =
    kLightTabRoomBudget == 0 ? std::string()
                             : "&tab_room_budget=" + std::to_string(kLightTabRoomBudget);

}  // namespace papernet::test
