#pragma once

#include <cstddef>
#include <string>

#include "engine/pipeline.h"

namespace papernet::cli {

/// A mesh file on this machine as the engine's input: its bytes and its format by extension
/// (else sniffed), and the files beside it that it names (a .gltf's buffers, an OBJ's `mtllib`
/// material libraries) when they are plain relative names inside its folder (never `..`, an
/// absolute path or a URL). `path` may be a folder that holds one model file (by extension),
/// such as a glTF with its buffers and textures: that file is read.
/// \throw IOException naming the fault (LimitExceededException over `max_bytes`).
JobInput read_local_input(const std::string& path, std::size_t max_bytes);

}  // namespace papernet::cli
