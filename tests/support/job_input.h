// A job's input from a file of tests/data, as the command line reads it.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/load.h"
#include "engine/pipeline.h"
#include "tests/support/paths.h"

namespace papernet::test {

/// A model file anywhere (the meshes of ../shared/data), read as the command line reads it.
inline JobInput file_input(const std::string& path) {
  JobInput input;
  input.mesh = read_mesh_file(path, 64 << 20);
  input.format = format_from_extension(path);
  return input;
}

/// A model of tests/data. One in a folder of its own (a .gltf with its buffers and images) comes
/// with the other files of that folder, as the command line reads those beside the file.
inline JobInput data_file(const std::string& name) {
  const std::filesystem::path path = std::filesystem::path(papernet::test::test_data_dir()) / name;
  JobInput input = file_input(path.string());
  if (name.find('/') != std::string::npos)
    for (const auto& entry : std::filesystem::directory_iterator(path.parent_path()))
      if (entry.path() != path && entry.is_regular_file())
        input.external_files[entry.path().filename().string()] =
            read_mesh_file(entry.path().string(), 64 << 20);
  return input;
}

/// The entry of a result's `warnings` or `repairs` with code `code`, or null.
inline const NetRepair* entry_of(const std::vector<NetRepair>& entries, std::string_view code) {
  for (const NetRepair& entry : entries)
    if (entry.code == code) return &entry;
  return nullptr;
}

}  // namespace papernet::test
