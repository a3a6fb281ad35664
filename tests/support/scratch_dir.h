#pragma once
// A directory of a test's own under the system's temporary directory, removed with everything in
// it when the test ends (files the program under test writes beside its outputs too: the
// textures beside a net's JSON).

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <system_error>

namespace papernet::test {

class ScratchDir {
 public:
  /// `name` and the process id and a counter: a fresh directory, also when tests run in parallel.
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              (name + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter()++))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// The path of `file` in the directory, as a string for a command line.
  std::string operator/(const std::string& file) const { return (path_ / file).string(); }

 private:
  static std::atomic<unsigned>& counter() {
    static std::atomic<unsigned> n{0};
    return n;
  }
  std::filesystem::path path_;
};

}  // namespace papernet::test
