// PLY reader (ascii, binary little and big endian). Reads x/y/z of "vertex" and the index list of
// "face"; every other element and property is parsed only to be skipped.
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>

#include "core/errors.h"
#include "core/io/internal/load_formats.h"

namespace papernet::detail {
namespace {

enum class Type { Char, UChar, Short, UShort, Int, UInt, Float, Double };

bool type_from_name(std::string_view name, Type& t) {
  static constexpr std::pair<std::string_view, Type> kNames[] = {
      {"char", Type::Char},     {"int8", Type::Char},     {"uchar", Type::UChar},
      {"uint8", Type::UChar},   {"short", Type::Short},   {"int16", Type::Short},
      {"ushort", Type::UShort}, {"uint16", Type::UShort}, {"int", Type::Int},
      {"int32", Type::Int},     {"uint", Type::UInt},     {"uint32", Type::UInt},
      {"float", Type::Float},   {"float32", Type::Float}, {"double", Type::Double},
      {"float64", Type::Double}};
  for (auto [n, type] : kNames)
    if (n == name) {
      t = type;
      return true;
    }
  return false;
}

std::size_t type_size(Type t) {
  switch (t) {
    case Type::Char:
    case Type::UChar:
      return 1;
    case Type::Short:
    case Type::UShort:
      return 2;
    case Type::Int:
    case Type::UInt:
    case Type::Float:
      return 4;
    case Type::Double:
      return 8;
  }
  return 1;
}

struct Property {
  std::string name;
  Type type = Type::Float;
  bool list = false;
  Type count_type = Type::UChar;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

/// Reads values in the file's encoding; every read checks that the data is there.
class Reader {
 public:
  Reader(std::string_view data, int encoding) : data_(data), encoding_(encoding) {}

  double read(Type t) {
    if (encoding_ == 0) return read_ascii();
    const std::size_t n = type_size(t);
    if (data_.size() < n) throw IOException("ply: the file ends inside its data");
    unsigned char b[8];
    std::memcpy(b, data_.data(), n);
    data_.remove_prefix(n);
    const bool little = encoding_ == 1;
    if (little != (std::endian::native == std::endian::little))
      for (std::size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    switch (t) {
      case Type::Char:
        return static_cast<std::int8_t>(b[0]);
      case Type::UChar:
        return b[0];
      case Type::Short:
        return load<std::int16_t>(b);
      case Type::UShort:
        return load<std::uint16_t>(b);
      case Type::Int:
        return load<std::int32_t>(b);
      case Type::UInt:
        return load<std::uint32_t>(b);
      case Type::Float:
        return load<float>(b);
      case Type::Double:
        return load<double>(b);
    }
    return 0;
  }

  std::size_t remaining() const { return data_.size(); }

  /// Ascii records are lines: values beyond those the header declares are ignored, as other
  /// readers do (some exporters write more than they declare).
  void end_record() {
    if (encoding_ != 0) return;
    const std::size_t eol = data_.find('\n');
    data_.remove_prefix(eol == std::string_view::npos ? data_.size() : eol + 1);
  }

 private:
  template <typename T>
  static T load(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }

  double read_ascii() {
    std::size_t i = 0;
    while (i < data_.size() && std::isspace(static_cast<unsigned char>(data_[i]))) ++i;
    std::size_t j = i;
    while (j < data_.size() && !std::isspace(static_cast<unsigned char>(data_[j]))) ++j;
    if (i == j) throw IOException("ply: the file ends inside its data");
    std::string_view tok = data_.substr(i, j - i);
    if (tok.front() == '+') tok.remove_prefix(1);
    double v = 0;
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (ec != std::errc() || end != tok.data() + tok.size())
      throw IOException("ply: bad number '" + std::string(data_.substr(i, j - i)) + "'");
    data_.remove_prefix(j);
    return v;
  }

  std::string_view data_;
  int encoding_;  // 0 ascii, 1 little endian, 2 big endian
};

/// Triangle strips as PLY writes them: -1 ends a strip; every other triangle is turned so that
/// all keep the strip's orientation; triangles with a repeated vertex (joins) are skipped.
void add_strips(RawMesh& out, const std::vector<long long>& strips, const LoadOptions& options) {
  std::vector<long long> tri(3);
  std::size_t start = 0;
  for (std::size_t i = 0; i + 2 < strips.size(); ++i) {
    if (strips[i] < 0 || strips[i + 1] < 0 || strips[i + 2] < 0) {
      if (strips[i] < 0) start = i + 1;
      continue;
    }
    const bool odd = (i - start) % 2 == 1;
    tri = {strips[i], strips[odd ? i + 2 : i + 1], strips[odd ? i + 1 : i + 2]};
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
    add_polygon(out, tri, options, "ply tristrips");
  }
  out.triangulated = true;
}

}  // namespace

RawMesh read_ply(std::string_view bytes, const LoadOptions& options) {
  const std::size_t end = bytes.find("end_header");
  if (bytes.substr(0, 3) != "ply" || end == std::string_view::npos)
    throw IOException("ply: no 'ply' ... 'end_header' header");
  std::size_t body = bytes.find('\n', end);
  body = body == std::string_view::npos ? bytes.size() : body + 1;
  int encoding = -1;
  std::vector<Element> elements;
  std::string_view header = bytes.substr(0, end);
  std::size_t pos = 0;
  while (pos < header.size()) {
    std::size_t eol = header.find('\n', pos);
    if (eol == std::string_view::npos) eol = header.size();
    std::string line(header.substr(pos, eol - pos));
    pos = eol + 1;
    std::vector<std::string> w;
    for (std::size_t i = 0; i < line.size();) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      std::size_t j = i;
      while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
      if (j > i) w.push_back(line.substr(i, j - i));
      i = j;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info" || w[0] == "ply") continue;
    if (w[0] == "format" && w.size() >= 2) {
      if (w[1] == "ascii")
        encoding = 0;
      else if (w[1] == "binary_little_endian")
        encoding = 1;
      else if (w[1] == "binary_big_endian")
        encoding = 2;
      else
        throw IOException("ply: unknown format '" + w[1] + "'");
    } else if (w[0] == "element" && w.size() == 3) {
      Element e;
      e.name = w[1];
      const auto [p, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (ec != std::errc() || p != w[2].data() + w[2].size())
        throw IOException("ply: bad count for element '" + w[1] + "'");
      elements.push_back(std::move(e));
    } else if (w[0] == "property" && !elements.empty()) {
      Property p;
      if (w.size() == 5 && w[1] == "list") {
        p.list = true;
        if (!type_from_name(w[2], p.count_type) || !type_from_name(w[3], p.type))
          throw IOException("ply: unknown list type in '" + line + "'");
        p.name = w[4];
      } else if (w.size() == 3 && type_from_name(w[1], p.type)) {
        p.name = w[2];
      } else {
        throw IOException("ply: bad property line '" + line + "'");
      }
      elements.back().properties.push_back(std::move(p));
    } else {
      throw IOException("ply: bad header line '" + line + "'");
    }
  }
  if (encoding < 0) throw IOException("ply: the header has no format line");

  Reader in(bytes.substr(body), encoding);
  RawMesh out;
  std::size_t short_faces = 0;
  std::vector<long long> poly;
  std::vector<RGBA> vertex_colours;  // per vertex, when the vertices have red, green and blue
  for (const Element& e : elements) {
    // Declared counts are checked against the bytes left before anything is reserved: a record
    // takes at least one byte per value in binary and two characters per value in ascii.
    std::size_t min_record = 0;
    for (const Property& p : e.properties)
      min_record += encoding == 0 ? 2 : (p.list ? type_size(p.count_type) : type_size(p.type));
    if (min_record == 0) continue;  // no properties: the records take no room at all
    if (e.count > in.remaining() / min_record)
      throw IOException("ply: element '" + e.name + "' declares " + std::to_string(e.count) +
                        " records but only " + std::to_string(in.remaining()) +
                        " bytes of data are left");
    const bool is_vertex = e.name == "vertex";
    const bool is_strips = e.name == "tristrips";
    const bool is_face = e.name == "face" || is_strips;
    int ix = -1, iy = -1, iz = -1, ilist = -1;
    int icolour[4] = {-1, -1, -1, -1};  // red, green, blue, alpha
    static constexpr std::string_view kChannels[] = {"red", "green", "blue", "alpha"};
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const Property& p = e.properties[k];
      if (is_vertex && !p.list && p.name == "x") ix = int(k);
      if (is_vertex && !p.list && p.name == "y") iy = int(k);
      if (is_vertex && !p.list && p.name == "z") iz = int(k);
      for (int c = 0; c < 4; ++c)
        if (is_vertex && !p.list &&
            (p.name == kChannels[c] || p.name == std::string("diffuse_").append(kChannels[c])))
          icolour[c] = int(k);
      if (is_face && p.list && (p.name == "vertex_indices" || p.name == "vertex_index"))
        ilist = int(k);
    }
    if (is_vertex && (ix < 0 || iy < 0 || iz < 0))
      throw IOException("ply: the vertex element lacks x, y or z");
    // Summed over elements: a file may declare "vertex" more than once.
    if (is_vertex) check_vertices(out.vertices.size() + e.count, options, "ply header");
    if (is_vertex) out.vertices.reserve(e.count);
    if (is_face) check_declared_faces(e.count, options, "ply header");
    const bool coloured = is_vertex && icolour[0] >= 0 && icolour[1] >= 0 && icolour[2] >= 0;
    for (std::uint64_t r = 0; r < e.count; ++r) {
      Vec3 v;
      RGBA colour{1, 1, 1, 1};
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (!p.list) {
          const double value = in.read(p.type);
          if (int(k) == ix) v.x = value;
          if (int(k) == iy) v.y = value;
          if (int(k) == iz) v.z = value;
          for (int c = 0; c < 4; ++c)
            if (int(k) == icolour[c])  // integers are 0..max of their type; floats 0..1
              colour[c] = p.type == Type::UChar    ? value / 255
                          : p.type == Type::UShort ? value / 65535
                                                   : value;
          continue;
        }
        // Each listed value takes room in the data that is left: a longer list is refused
        // before the face's index vector is sized for it.
        const double n = in.read(p.count_type);
        const std::size_t value_room = encoding == 0 ? 2 : type_size(p.type);
        if (!(n >= 0) || n > double((in.remaining() + 1) / value_room))
          throw IOException("ply: bad list length in element '" + e.name + "'");
        if (int(k) == ilist) poly.assign(static_cast<std::size_t>(n), 0);
        for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
          const double value = in.read(p.type);
          if (int(k) == ilist) {
            if (!(value >= -1e15 && value <= 1e15))
              throw IOException("ply: bad vertex index in face " + std::to_string(r));
            poly[i] = static_cast<long long>(value);
          }
        }
      }
      in.end_record();
      if (is_vertex) out.vertices.push_back(v);
      if (coloured) {
        vertex_colours.resize(out.vertices.size(), RGBA{1, 1, 1, 1});
        vertex_colours.back() = colour;
      }
      if (is_strips && ilist >= 0) {
        add_strips(out, poly, options);
      } else if (is_face && ilist >= 0) {
        if (poly.size() < 3) ++short_faces;
        add_polygon(out, poly, options, "ply face " + std::to_string(r));
      }
    }
  }
  if (!vertex_colours.empty()) {
    vertex_colours.resize(out.vertices.size(), RGBA{1, 1, 1, 1});
    out.colour.colours.resize(out.faces.size());
    for (std::size_t f = 0; f < out.faces.size(); ++f)
      for (int k = 0; k < 3; ++k) out.colour.colours[f][k] = vertex_colours[out.faces[f][k]];
  }
  if (short_faces)
    out.notes.push_back(std::to_string(short_faces) +
                        " faces with fewer than 3 vertices were skipped");
  return out;
}

}  // namespace papernet::detail
