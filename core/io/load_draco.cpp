// Draco streams: the header and connectivity counts are read and checked here before
// draco::Decoder sees the stream, because the decoder sizes its tables from those counts
// (an edgebreaker stream declaring 2^30 faces would make it reserve gigabytes).
#include <draco/compression/decode.h>

#include <cstdint>
#include <cstring>

#include "core/errors.h"
#include "core/io/internal/load_formats.h"

namespace papernet::detail {
namespace {

/// Bounds-checked little-endian reads over the stream; every failure names what was cut short.
class Bytes {
 public:
  explicit Bytes(std::string_view s) : s_(s) {}

  std::uint32_t u8(const char* what) { return take(1, what)[0]; }
  std::uint32_t u16(const char* what) {
    const auto* b = take(2, what);
    return b[0] | (std::uint32_t{b[1]} << 8);
  }
  std::uint32_t u32(const char* what) {
    const auto* b = take(4, what);
    return b[0] | (std::uint32_t{b[1]} << 8) | (std::uint32_t{b[2]} << 16) |
           (std::uint32_t{b[3]} << 24);
  }
  std::uint32_t varint(const char* what) {
    std::uint64_t v = 0;
    for (int shift = 0; shift < 35; shift += 7) {
      const std::uint32_t b = u8(what);
      v |= std::uint64_t{b & 0x7f} << shift;
      if (!(b & 0x80)) {
        if (v > 0xffffffffull) break;
        return static_cast<std::uint32_t>(v);
      }
    }
    throw IOException(std::string("drc: bad variable-length number in ") + what);
  }
  void skip(std::uint64_t n, const char* what) {
    if (n > s_.size()) throw IOException(std::string("drc: the stream ends inside ") + what);
    s_.remove_prefix(static_cast<std::size_t>(n));
  }
  std::size_t remaining() const { return s_.size(); }

 private:
  const unsigned char* take(std::size_t n, const char* what) {
    if (s_.size() < n) throw IOException(std::string("drc: the stream ends inside ") + what);
    const auto* p = reinterpret_cast<const unsigned char*>(s_.data());
    s_.remove_prefix(n);
    return p;
  }
  std::string_view s_;
};

void skip_metadata(Bytes& in, int depth) {
  // Mirrors draco's metadata layout; checked here because the decoder allocates each entry's
  // declared size and recurses into sub-metadata without a depth bound.
  if (depth > 32) throw IOException("drc: metadata nested deeper than 32 levels");
  const std::uint32_t entries = in.varint("metadata");
  if (entries > in.remaining()) throw IOException("drc: metadata declares too many entries");
  for (std::uint32_t i = 0; i < entries; ++i) {
    in.skip(in.u8("metadata name"), "metadata name");
    const std::uint32_t size = in.varint("metadata entry");
    if (size == 0) throw IOException("drc: an empty metadata entry");
    in.skip(size, "metadata entry");
  }
  const std::uint32_t subs = in.varint("metadata");
  if (subs > in.remaining()) throw IOException("drc: metadata declares too many sub-metadata");
  for (std::uint32_t i = 0; i < subs; ++i) {
    in.skip(in.u8("metadata name"), "metadata name");
    skip_metadata(in, depth + 1);
  }
}

/// Reads the header and connectivity counts and refuses what the limits or the stream size
/// cannot back.
void check_header(std::string_view bytes, const LoadOptions& options) {
  Bytes in(bytes);
  in.skip(5, "the header");
  if (bytes.substr(0, 5) != "DRACO") throw IOException("drc: no DRACO magic");
  const std::uint32_t major = in.u8("the header"), minor = in.u8("the header");
  const std::uint32_t type = in.u8("the header"), method = in.u8("the header");
  const std::uint32_t flags = in.u16("the header");
  const std::uint32_t version = major << 8 | minor;
  if (type == 0) throw IOException("drc: the stream is a point cloud, not a triangle mesh");
  if (type != 1) throw IOException("drc: unknown geometry type " + std::to_string(type));
  if (major < 1 || version > 0x0202)
    throw IOException("drc: unsupported bitstream version " + std::to_string(major) + "." +
                      std::to_string(minor));
  if (version >= 0x0103 && (flags & 0x8000)) {
    const std::uint32_t attributes = in.varint("metadata");
    if (attributes > in.remaining())
      throw IOException("drc: metadata declares too many attributes");
    for (std::uint32_t i = 0; i < attributes; ++i) {
      in.varint("metadata");
      skip_metadata(in, 0);
    }
    skip_metadata(in, 0);
  }
  auto count = [&](const char* what, bool fixed) { return fixed ? in.u32(what) : in.varint(what); };
  std::uint64_t faces = 0, points = 0;
  if (method == 0) {
    faces = count("the face count", version < 0x0202);
    points = count("the point count", version < 0x0202);
  } else if (method == 1) {
    in.u8("the traversal type");
    if (version < 0x0202) count("the new vertex count", version < 0x0200);
    points = count("the vertex count", version < 0x0200);
    faces = count("the face count", version < 0x0200);
    in.u8("the attribute count");
    count("the symbol count", version < 0x0200);
    const std::uint64_t splits = count("the split symbol count", version < 0x0200);
    if (splits > faces)
      throw IOException("drc: " + std::to_string(splits) + " split symbols for " +
                        std::to_string(faces) + " faces");
    points += splits;
  } else {
    throw IOException("drc: unknown encoding method " + std::to_string(method));
  }
  check_declared_faces(faces, options, "drc header");
  if (points > 3 * faces + 3)
    throw IOException("drc: the header declares " + std::to_string(points) + " points for " +
                      std::to_string(faces) + " faces");
  check_vertices(points, options, "drc header");
}

// Draco converts stored values by reading them as their declared type: bytes declared bool that
// are neither 0 nor 1 are undefined behaviour there (found by fuzz_draco). Attributes we or
// tinygltf convert must be numbers.
void check_number_type(const draco::PointAttribute& attribute, const std::string& what) {
  switch (attribute.data_type()) {
    case draco::DT_INT8:
    case draco::DT_UINT8:
    case draco::DT_INT16:
    case draco::DT_UINT16:
    case draco::DT_INT32:
    case draco::DT_UINT32:
    case draco::DT_INT64:
    case draco::DT_UINT64:
    case draco::DT_FLOAT32:
    case draco::DT_FLOAT64:
      return;
    default:
      throw IOException("drc: " + what + " have data type " +
                        std::to_string(static_cast<int>(attribute.data_type())) +
                        ", not a number type (Draco DT_INT8 to DT_FLOAT64)");
  }
}

}  // namespace

RawMesh read_draco(std::string_view bytes, const LoadOptions& options, int position_id,
                   const std::vector<int>& required_ids) {
  check_header(bytes, options);
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok())
    throw IOException(std::string("drc: cannot decode: ") + decoded.status().error_msg());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  const draco::PointAttribute* position =
      position_id >= 0 ? mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(position_id))
                       : mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (position == nullptr) throw IOException("drc: the mesh has no position attribute");
  for (int id : required_ids) {
    const draco::PointAttribute* a = mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id));
    if (a == nullptr)
      throw IOException("drc: the stream has no attribute with id " + std::to_string(id));
    check_number_type(*a, "values of attribute " + std::to_string(id));  // tinygltf converts it too
  }
  if (position->num_components() < 3)
    throw IOException("drc: positions have fewer than 3 components");
  check_number_type(*position, "positions");
  RawMesh out;
  out.vertices.reserve(mesh->num_points());
  for (draco::PointIndex i(0); i < mesh->num_points(); ++i) {
    double p[3] = {0, 0, 0};
    if (!position->ConvertValue<double>(position->mapped_index(i), 3, p))
      throw IOException("drc: cannot convert a position");
    out.vertices.push_back({p[0], p[1], p[2]});
  }
  out.faces.reserve(mesh->num_faces());
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
    const auto& face = mesh->face(f);
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k) {
      if (face[k].value() >= mesh->num_points()) throw IOException("drc: face index out of range");
      t[k] = static_cast<int>(face[k].value());
    }
    out.faces.push_back(t);
  }
  if (out.faces.size() > options.max_faces) check_declared_faces(out.faces.size(), options, "drc");
  return out;
}

}  // namespace papernet::detail
