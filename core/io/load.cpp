// Loading: format names and sniffing, dispatch to the per-format readers, welding, limits.
// Every reader works on bytes in memory; nothing here reads a path a file names.
#include "core/io/load.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unordered_map>

#include "core/errors.h"
#include "core/io/internal/load_formats.h"

namespace papernet {
namespace detail {

void check_declared_faces(std::size_t count, const LoadOptions& options, std::string_view what) {
  if (count > options.max_faces)
    throw LimitExceededException(LimitExceededException::Limit::Faces,
                                 std::string(what) + " declares " + std::to_string(count) +
                                     " faces, more than the limit of " +
                                     std::to_string(options.max_faces));
}

void check_vertices(std::size_t count, const LoadOptions& options, std::string_view what) {
  if (count > options.max_vertices)
    throw LimitExceededException(LimitExceededException::Limit::Vertices,
                                 std::string(what) + " has " + std::to_string(count) +
                                     " vertices, more than the limit of " +
                                     std::to_string(options.max_vertices));
}

void add_polygon(RawMesh& out, const std::vector<long long>& poly, const LoadOptions& options,
                 std::string_view where) {
  const long long n = static_cast<long long>(out.vertices.size());
  for (long long v : poly)
    if (v < 0 || v >= n)
      throw IOException(std::string(where) + ": vertex index " + std::to_string(v) +
                        " out of range (" + std::to_string(n) + " vertices)");
  if (poly.size() < 3) return;  // counted by the caller, which knows what the entry was
  if (poly.size() > 3) out.triangulated = true;
  if (out.faces.size() + poly.size() - 2 > options.max_faces)
    throw LimitExceededException(
        LimitExceededException::Limit::Faces,
        "more than the limit of " + std::to_string(options.max_faces) + " faces");
  for (std::size_t k = 1; k + 1 < poly.size(); ++k)
    out.faces.push_back({int(poly[0]), int(poly[k]), int(poly[k + 1])});
}

bool make_texture(std::string name, std::string bytes, const LoadOptions& options,
                  const std::string& what, Texture& out, std::vector<std::string>& notes) {
  out.name = std::move(name);
  try {
    const Image decoded = decode_image(bytes, options.max_image_pixels);
    out.width = decoded.width;
    out.height = decoded.height;
  } catch (const LimitExceededException&) {
    throw;
  } catch (const IOException& e) {
    notes.push_back("texture image '" + out.name + "' cannot be used (" + e.what() + "); " + what +
                    " is printed without it");
    return false;
  }
  out.mime_type = image_mime_type(sniff_image(bytes));
  out.bytes = std::move(bytes);
  return true;
}

}  // namespace detail

namespace {

bool starts_with_ci(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[i])) != prefix[i]) return false;
  return true;
}

std::string_view skip_space(std::string_view s) {
  std::size_t i = 0;
  // A UTF-8 byte order mark is skipped too: text exporters on Windows write one.
  if (s.substr(0, 3) == "\xEF\xBB\xBF") i = 3;
  while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  return s.substr(i);
}

bool looks_like_obj(std::string_view s) {
  // Every non-empty line of the first few must start with an OBJ keyword or a comment.
  int seen = 0;
  std::size_t pos = 0;
  while (pos < s.size() && seen < 20) {
    std::size_t end = s.find('\n', pos);
    if (end == std::string_view::npos) end = s.size();
    std::string_view line = skip_space(s.substr(pos, end - pos));
    pos = end + 1;
    if (line.empty()) continue;
    const std::size_t word_end = line.find_first_of(" \t\r");
    const std::string_view word = line.substr(0, word_end);
    static constexpr std::string_view kKeywords[] = {"#", "v", "vt", "vn", "vp",     "f",     "l",
                                                     "p", "o", "g",  "s",  "usemtl", "mtllib"};
    if (word.front() != '#' &&
        std::find(std::begin(kKeywords), std::end(kKeywords), word) == std::end(kKeywords))
      return false;
    ++seen;
  }
  return seen > 0;
}

struct PositionHash {
  std::size_t operator()(const Vec3& p) const {
    std::uint64_t h = 1469598103934665603ull;
    for (double c : {p.x, p.y, p.z}) h = (h ^ std::bit_cast<std::uint64_t>(c)) * 1099511628211ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};
struct PositionEqual {
  bool operator()(const Vec3& a, const Vec3& b) const { return a == b; }
};

/// Merges vertices with equal positions and drops unreferenced ones. Non-finite positions are
/// never merged (NaN equals nothing), so validation still sees and reports them.
LoadedMesh weld(detail::RawMesh raw, MeshFormat format) {
  LoadedMesh out;
  out.format = format;
  out.raw_vertices = raw.vertices.size();
  out.triangulated = raw.triangulated;
  out.notes = std::move(raw.notes);
  out.colour = std::move(raw.colour);
  std::vector<char> used(raw.vertices.size(), 0);
  for (const auto& f : raw.faces)
    for (int v : f) used[v] = 1;
  std::unordered_map<Vec3, int, PositionHash, PositionEqual> index;
  std::vector<int> remap(raw.vertices.size(), -1);
  std::size_t unused = 0;
  for (std::size_t i = 0; i < raw.vertices.size(); ++i) {
    if (!used[i]) {
      ++unused;
      continue;
    }
    Vec3 p = raw.vertices[i];
    p = {p.x + 0.0, p.y + 0.0, p.z + 0.0};  // -0.0 becomes 0.0: equal positions, equal bits
    const int next = static_cast<int>(out.mesh.vertices.size());
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      remap[i] = next;
      out.mesh.vertices.push_back(raw.vertices[i]);
      continue;
    }
    auto [it, fresh] = index.try_emplace(p, next);
    if (fresh) out.mesh.vertices.push_back(p);
    remap[i] = it->second;
  }
  out.mesh.faces.reserve(raw.faces.size());
  for (const auto& f : raw.faces) out.mesh.faces.push_back({remap[f[0]], remap[f[1]], remap[f[2]]});
  out.raw_faces = std::move(raw.faces);
  if (unused > 0)
    out.notes.push_back(std::to_string(unused) + " vertices used by no face were dropped");
  return out;
}

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

MeshFormat sniff_format(std::string_view bytes) {
  if (bytes.substr(0, 4) == "glTF") return MeshFormat::Glb;
  if (bytes.substr(0, 5) == "DRACO") return MeshFormat::Draco;
  if (bytes.size() >= 84) {
    // Binary STL: an 80-byte header, a triangle count, 50 bytes per triangle. Checked before
    // "solid" because many binary STL headers start with that word.
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (84 + 50 * std::uint64_t{count} == bytes.size()) return MeshFormat::Stl;
  }
  const std::string_view text = skip_space(bytes);
  if (text.empty()) return MeshFormat::Unknown;
  if (text.front() == '{') return MeshFormat::Gltf;
  if (text.substr(0, 3) == "ply") return MeshFormat::Ply;
  const std::size_t off = text.find("OFF");
  if (off != std::string_view::npos && off <= 4 &&
      std::all_of(text.begin(), text.begin() + off, [](char c) { return std::isupper(c); }))
    return MeshFormat::Off;
  if (starts_with_ci(text, "solid")) return MeshFormat::Stl;
  if (looks_like_obj(text)) return MeshFormat::Obj;
  return MeshFormat::Unknown;
}

LoadedMesh load_mesh(std::string_view bytes, MeshFormat format, const LoadOptions& options) {
  if (bytes.size() > options.max_bytes)
    throw LimitExceededException(LimitExceededException::Limit::Bytes,
                                 "the file has " + std::to_string(bytes.size()) +
                                     " bytes, more than the limit of " +
                                     std::to_string(options.max_bytes));
  if (bytes.empty()) throw IOException("the file is empty");
  if (format == MeshFormat::Unknown) format = sniff_format(bytes);
  detail::RawMesh raw;
  switch (format) {
    case MeshFormat::Obj:
      raw = detail::read_obj(bytes, options);
      break;
    case MeshFormat::Off:
      raw = detail::read_off(bytes, options);
      break;
    case MeshFormat::Ply:
      raw = detail::read_ply(bytes, options);
      break;
    case MeshFormat::Stl:
      raw = detail::read_stl(bytes, options);
      break;
    case MeshFormat::Gltf:
    case MeshFormat::Glb:
      raw = detail::read_gltf(bytes, format == MeshFormat::Glb, options);
      break;
    case MeshFormat::Draco:
      raw = detail::read_draco(bytes, options);
      break;
    case MeshFormat::Unknown:
      throw IOException(
          "unsupported or unrecognised format (expected glb, gltf, drc, obj, off, ply or stl)");
  }
  return weld(std::move(raw), format);
}

std::string read_mesh_file(const std::string& path, std::size_t max_bytes) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw IOException("cannot open " + path + ": " + ec.message());
  if (size > max_bytes)
    throw LimitExceededException(LimitExceededException::Limit::Bytes,
                                 "the file has " + std::to_string(size) +
                                     " bytes, more than the limit of " + std::to_string(max_bytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IOException("cannot open " + path);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (in.gcount() != static_cast<std::streamsize>(size)) throw IOException("cannot read " + path);
  return bytes;
}

LoadedMesh load_mesh_file(const std::string& path, const LoadOptions& options) {
  return load_mesh(read_mesh_file(path, options.max_bytes), format_from_extension(path), options);
}

}  // namespace papernet
