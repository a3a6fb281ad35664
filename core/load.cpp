// First cut: OBJ/OFF/PLY/STL through OpenMesh's readers, welded. glTF and Draco come next.
#include "core/load.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "core/errors.h"

namespace papernet {
namespace {

struct OmTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<OmTraits>;

}  // namespace

std::string format_name(MeshFormat format) {
  switch (format) {
    case MeshFormat::Obj:
      return "obj";
    case MeshFormat::Off:
      return "off";
    case MeshFormat::Ply:
      return "ply";
    case MeshFormat::Stl:
      return "stl";
    case MeshFormat::Gltf:
      return "gltf";
    case MeshFormat::Glb:
      return "glb";
    case MeshFormat::Draco:
      return "drc";
    case MeshFormat::Unknown:
      break;
  }
  return "unknown";
}

MeshFormat format_from_extension(std::string_view path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".off") return MeshFormat::Off;
  if (ext == ".ply") return MeshFormat::Ply;
  if (ext == ".stl") return MeshFormat::Stl;
  if (ext == ".gltf") return MeshFormat::Gltf;
  if (ext == ".glb") return MeshFormat::Glb;
  if (ext == ".drc") return MeshFormat::Draco;
  return MeshFormat::Unknown;
}

LoadedMesh load_mesh(std::string_view bytes, MeshFormat format, const LoadOptions& options) {
  if (bytes.size() > options.max_bytes) throw IOException("file is larger than the limit");
  PolyMesh pm;
  std::istringstream in{std::string(bytes)};
  OpenMesh::IO::Options opt;
  if (!OpenMesh::IO::read_mesh(pm, in, format_name(format), opt))
    throw IOException("cannot read " + format_name(format) + " data");
  LoadedMesh out;
  out.format = format;
  out.raw_vertices = pm.n_vertices();
  std::map<std::tuple<double, double, double>, int> weld;
  std::vector<int> remap(pm.n_vertices());
  for (auto vh : pm.vertices()) {
    const auto& p = pm.point(vh);
    auto [it, fresh] = weld.try_emplace({p[0], p[1], p[2]}, int(out.mesh.vertices.size()));
    if (fresh) out.mesh.vertices.push_back({p[0], p[1], p[2]});
    remap[vh.idx()] = it->second;
  }
  for (auto fh : pm.faces()) {
    std::vector<int> poly;
    for (auto vh : pm.fv_range(fh)) poly.push_back(remap[vh.idx()]);
    if (poly.size() > 3) out.triangulated = true;
    for (std::size_t k = 1; k + 1 < poly.size(); ++k)
      out.mesh.faces.push_back({poly[0], poly[k], poly[k + 1]});
  }
  if (out.mesh.faces.size() > options.max_faces) throw IOException("too many faces");
  return out;
}

LoadedMesh load_mesh_file(const std::string& path, const LoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IOException("cannot open " + path);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return load_mesh(bytes, format_from_extension(path), options);
}

}  // namespace papernet
