#pragma once
// Where the tests find what lies outside them. The absolute paths of this checkout and build are
// compiled once, in a file tests/CMakeLists.txt generates, not given to every test source as
// compile definitions: so ccache shares the test sources' objects between clones at other paths
// (a path in a definition is part of every object's hash).

#include <string>

namespace papernet::test {

/// tests/data of this checkout.
std::string test_data_dir();
/// ../shared/data beside this checkout (it may be absent: the tests that need it say they skip).
std::string shared_data_dir();
/// The papernet program of this build.
std::string papernet_binary();

}  // namespace papernet::test
