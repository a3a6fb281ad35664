#pragma once
// Which sanitizer the test is built with (make sanitize): tests that would measure the speed of
// a sanitized build rather than its correctness keep their work smaller there.

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
