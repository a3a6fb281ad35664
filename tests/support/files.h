#pragma once
// Files the tests read whole: outputs a program wrote, meshes handed to the loader as bytes.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/support/paths.h"

namespace papernet::test {

/// The bytes of the file at `path` (empty when it cannot be read).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The bytes of the mesh file `name` in tests/data.
inline std::string test_mesh(const std::string& name) {
  return read_file(std::filesystem::path(test_data_dir()) / name);
}

}  // namespace papernet::test
