#pragma once
// Shared by the fuzz targets: what the service does with an upload once it is parsed.

#include <map>
#include <string>
#include <string_view>

#include "core/io/load.h"

namespace papernet::fuzz {

/// Loads `bytes` as the service's worker does (engine/pipeline.h: the default
/// PipelineLimits, so max_bytes 64 MiB and 4 x 1,000,000 + 16 faces) and validates what loaded,
/// once as it is and once keeping the largest component; then repairs it (core/mesh/repair.h)
/// and aborts when the repaired mesh fails validation for anything but being in several parts
/// (or empty) or its parts lose a face. IOException is the loader's promised
/// answer to bad input and is swallowed (after checking it says something); any other exception
/// escapes, and libFuzzer reports it as a crash.
void load_and_validate(std::string_view bytes, MeshFormat format,
                       const std::map<std::string, std::string>& external_files = {});

}  // namespace papernet::fuzz
