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

// The tab room pass runs 10-20 times slower sanitized: there, service jobs of tests that are not
// about the pass give it a tenth of its default budget (a query option to append), so that a job
// takes seconds, not minutes (sample.obj's TU net keeps 12 tabs to each strip).
#ifdef PAPERNET_TEST_SANITIZED
inline const std::string kTabRoomQuery = "&tab_room_budget=10000";
#else
inline const std::string kTabRoomQuery;
#endif

/// The same for a job a test runs itself: `budget` (JobOptions::tab_room_budget), at most a tenth
/// of the default sanitized.
constexpr std::size_t light_tab_room(std::size_t budget) {
#ifdef PAPERNET_TEST_SANITIZED
  return std::min<std::size_t>(budget, 10'000);
#else
  return budget;
#endif
}

}  // namespace papernet::test
