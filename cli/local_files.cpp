#include "cli/local_files.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
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

/// The files beside the model that it names: a .gltf's buffers (and images), an OBJ's
/// material libraries.
std::vector<std::string> named_files(const JobInput& input) {
  if (input.format == MeshFormat::Gltf) {
    try {
      return gltf_external_uris(input.mesh);
    } catch (const IOException&) {
      return {};  // the loader says what is wrong with the file
    }
  }
  std::vector<std::string> names;
  if (input.format != MeshFormat::Obj) return names;
  std::istringstream lines(input.mesh);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string keyword, name;
    if (words >> keyword && keyword == "mtllib")
      while (words >> name) names.push_back(name);
  }
  return names;
}

/// The images an MTL file names (map_Kd: options first, the file name last).
std::vector<std::string> mtl_images(const std::string& mtl) {
  std::vector<std::string> names;
  std::istringstream lines(mtl);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string keyword, word, last;
    if (!(words >> keyword) || keyword != "map_Kd") continue;
    while (words >> word) last = word;
    if (!last.empty()) names.push_back(last);
  }
  return names;
}

/// Reads the files beside `path` that the model names, so that they come "with the upload";
/// for an OBJ, then the images its MTL files name.
void add_siblings(const std::string& path, std::size_t max_bytes, JobInput& input) {
  const auto dir = std::filesystem::path(path).parent_path();
  std::vector<std::string> names = named_files(input);
  const std::size_t libraries = names.size();  // an OBJ's MTL files come first
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string name = names[i];
    if (!safe_relative_name(name)) continue;  // never supplied: loading names it as missing
    const auto sibling = dir / name;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(sibling, ec)) continue;
    if (std::filesystem::file_size(sibling, ec) > max_bytes) continue;
    std::ifstream s(sibling, std::ios::binary);
    std::string& bytes = input.external_files[name];
    bytes.assign(std::istreambuf_iterator<char>(s), std::istreambuf_iterator<char>());
    if (input.format == MeshFormat::Obj && i < libraries && names.size() < 256)
      for (std::string& image : mtl_images(bytes)) names.push_back(std::move(image));
  }
}

/// The one model file in folder `dir` (a glTF folder as downloaded: the .gltf beside its
/// buffers and images; an OBJ beside its MTL and textures).
std::string model_in_folder(const std::string& dir) {
  std::vector<std::string> models;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.is_regular_file(ec) &&
        format_from_extension(entry.path().string()) != MeshFormat::Unknown)
      models.push_back(entry.path().filename().string());
  if (ec) throw IOException("cannot read the folder " + dir + ": " + ec.message());
  if (models.size() == 1) return (std::filesystem::path(dir) / models.front()).string();
  if (models.empty())
    throw IOException(
        "the folder holds no model file (expected glb, gltf, drc, obj, off, ply or stl)");
  std::sort(models.begin(), models.end());
  std::string list;
  for (std::size_t i = 0; i < models.size() && i < 5; ++i) list += (i > 0 ? ", " : "") + models[i];
  if (models.size() > 5) list += ", ...";
  throw IOException("the folder holds " + std::to_string(models.size()) + " model files (" + list +
                    "): name the one to unfold");
}

}  // namespace

JobInput read_local_input(const std::string& path, std::size_t max_bytes) {
  std::error_code ec;
  const std::string file = std::filesystem::is_directory(path, ec) ? model_in_folder(path) : path;
  JobInput input;
  input.mesh = read_mesh_file(file, max_bytes);
  input.format = format_from_extension(file);
  add_siblings(file, max_bytes, input);
  return input;
}

}  // namespace papernet::cli
