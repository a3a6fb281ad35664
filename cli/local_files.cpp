#include "cli/local_files.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "core/errors.h"

namespace papernet::cli {
namespace {

/// A buffer name a .gltf may use to reach a sibling file: relative, inside the folder.
bool safe_relative_name(const std::string& uri) {
  if (uri.empty() || uri.find("://") != std::string::npos || uri.find(':') != std::string::npos ||
      uri.front() == '/' || uri.find('\\') != std::string::npos)
    return false;
  for (const auto& part : std::filesystem::path(uri))
    if (part == "..") return false;
  return true;
}

/// Reads the sibling files a .gltf's buffers name, so that they come "with the upload".
void add_gltf_siblings(const std::string& path, std::size_t max_bytes, JobInput& input) {
  std::vector<std::string> uris;
  try {
    uris = gltf_external_uris(input.mesh);
  } catch (const IOException&) {
    return;  // the loader says what is wrong with the file
  }
  const auto dir = std::filesystem::path(path).parent_path();
  for (const std::string& uri : uris) {
    if (!safe_relative_name(uri)) continue;  // never supplied: loading names it as missing
    const auto sibling = dir / uri;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(sibling, ec)) continue;
    if (std::filesystem::file_size(sibling, ec) > max_bytes) continue;
    std::ifstream s(sibling, std::ios::binary);
    input.external_files[uri].assign(std::istreambuf_iterator<char>(s),
                                     std::istreambuf_iterator<char>());
  }
}

}  // namespace

JobInput read_local_input(const std::string& path, std::size_t max_bytes) {
  JobInput input;
  input.mesh = read_mesh_file(path, max_bytes);
  input.format = format_from_extension(path);
  if (input.format == MeshFormat::Gltf) add_gltf_siblings(path, max_bytes, input);
  return input;
}

}  // namespace papernet::cli
