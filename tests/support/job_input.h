// A job's input from a file of tests/data, as the command line reads it.
#pragma once

#include <string>

#include "core/io/load.h"
#include "engine/pipeline.h"

namespace papernet::test {

inline JobInput data_file(const std::string& name) {
  JobInput input;
  input.mesh = read_mesh_file(std::string(PAPERNET_TEST_DATA) + "/" + name, 64 << 20);
  input.format = format_from_extension(name);
  return input;
}

}  // namespace papernet::test
