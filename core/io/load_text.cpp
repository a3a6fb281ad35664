// OBJ, OFF and STL readers. Written by hand rather than through OpenMesh's readers: those build a
// halfedge mesh and silently drop faces that would make it non-manifold, which would hide from
// validation exactly the faults it must report. Here every face of the file is kept.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>

#include "core/errors.h"
#include "core/io/internal/load_formats.h"

namespace papernet::detail {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

/// Splits off the next whitespace-separated token of `s`.
std::string_view next_token(std::string_view& s) {
  std::size_t i = 0;
  while (i < s.size() && is_space(s[i])) ++i;
  std::size_t j = i;
  while (j < s.size() && !is_space(s[j])) ++j;
  std::string_view tok = s.substr(i, j - i);
  s.remove_prefix(j);
  return tok;
}

bool parse_double(std::string_view tok, double& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
  const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  return ec == std::errc() && end == tok.data() + tok.size();
}

bool parse_int(std::string_view tok, long long& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
  const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  return ec == std::errc() && end == tok.data() + tok.size();
}

/// Splits text into lines (without the newline), calling `fn(line, number)`.
template <typename Fn>
void for_each_line(std::string_view s, Fn fn) {
  std::size_t pos = 0, number = 0;
  while (pos < s.size()) {
    std::size_t end = s.find('\n', pos);
    if (end == std::string_view::npos) end = s.size();
    fn(s.substr(pos, end - pos), ++number);
    pos = end + 1;
  }
}

std::string at_line(std::string_view format, std::size_t line) {
  return std::string(format) + " line " + std::to_string(line);
}

/// An OBJ's materials as its MTL files define them (newmtl, Kd, d / Tr, map_Kd), by name.
class ObjMaterials {
 public:
  ObjMaterials(const LoadOptions& options, MeshColour& colour, std::vector<std::string>& notes)
      : options_(options), colour_(colour), notes_(notes) {}

  /// Reads an MTL file named by `mtllib`, from the files supplied with the model.
  void library(const std::string& name) {
    const auto file = options_.external_files.find(name);
    if (file == options_.external_files.end()) {
      notes_.push_back("material library '" + name + "' was not supplied with the model");
      return;
    }
    int current = -1;
    for_each_line(file->second, [&](std::string_view line, std::size_t) {
      while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
      line = line.substr(0, line.find('#'));
      const std::string_view keyword = next_token(line);
      if (keyword == "newmtl") {
        current = material(std::string(next_token(line)));
        return;
      }
      if (current < 0) return;
      Material& m = colour_.materials[std::size_t(current)];
      double x = 0;
      if (keyword == "Kd") {
        for (int k = 0; k < 3; ++k)
          if (parse_double(next_token(line), x)) m.base_color[std::size_t(k)] = x;
      } else if (keyword == "d" && parse_double(next_token(line), x)) {
        m.base_color[3] = x;
      } else if (keyword == "Tr" && parse_double(next_token(line), x)) {
        m.base_color[3] = 1 - x;
      } else if (keyword == "map_Kd") {
        std::string_view image;  // options (-s, -o, ...) come first: the name is the last word
        for (std::string_view tok = next_token(line); !tok.empty(); tok = next_token(line))
          image = tok;
        m.texture = texture(std::string(image));
      }
    });
  }

  /// The index of material `name`, made (white, untextured) when no MTL defined it.
  int material(const std::string& name) {
    const auto [it, fresh] = index_.try_emplace(name, int(colour_.materials.size()));
    if (fresh) colour_.materials.push_back({name, {1, 1, 1, 1}, -1});
    return it->second;
  }

 private:
  int texture(const std::string& name) {
    const auto known = textures_.find(name);
    if (known != textures_.end()) return known->second;
    int& ours = textures_[name] = -1;
    const auto file = options_.external_files.find(name);
    if (file == options_.external_files.end()) {
      notes_.push_back("texture image '" + name +
                       "' was not supplied with the model; its material is printed without it");
      return -1;
    }
    Texture t;
    if (!make_texture(name, file->second, options_, "its material", t, notes_)) return -1;
    ours = int(colour_.textures.size());
    colour_.textures.push_back(std::move(t));
    return ours;
  }

  const LoadOptions& options_;
  MeshColour& colour_;
  std::vector<std::string>& notes_;
  std::map<std::string, int> index_, textures_;
};

}  // namespace

RawMesh read_obj(std::string_view bytes, const LoadOptions& options) {
  RawMesh out;
  std::size_t short_faces = 0, lines = 0, points = 0;
  std::vector<long long> poly, poly_uvs;
  std::vector<UV> uvs;  // vt, v flipped: glTF's convention (docs/colour.md)
  ObjMaterials materials(options, out.colour, out.notes);
  int material = -1;   // usemtl
  std::string joined;  // a statement continued over lines with a trailing backslash
  std::size_t joined_from = 0;
  auto statement = [&](std::string_view line, std::size_t number) {
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    const std::string_view keyword = next_token(line);
    if (keyword == "v") {
      Vec3 p;
      if (!parse_double(next_token(line), p.x) || !parse_double(next_token(line), p.y) ||
          !parse_double(next_token(line), p.z))
        throw IOException(at_line("obj", number) + ": a vertex needs three numbers");
      check_vertices(out.vertices.size() + 1, options, "obj");
      out.vertices.push_back(p);
    } else if (keyword == "vt") {
      UV uv{0, 0};
      if (!parse_double(next_token(line), uv[0])) uv[0] = std::nan("");
      std::string_view v = next_token(line);
      if (!v.empty() && !parse_double(v, uv[1])) uv[1] = std::nan("");
      check_vertices(uvs.size() + 1, options, "obj texture coordinates");
      uvs.push_back({uv[0], 1 - uv[1]});
    } else if (keyword == "mtllib") {
      for (std::string_view tok = next_token(line); !tok.empty(); tok = next_token(line))
        materials.library(std::string(tok));
    } else if (keyword == "usemtl") {
      material = materials.material(std::string(next_token(line)));
    } else if (keyword == "f") {
      poly.clear();
      poly_uvs.clear();
      const long long n = static_cast<long long>(out.vertices.size());
      for (std::string_view tok = next_token(line); !tok.empty(); tok = next_token(line)) {
        long long index = 0;
        if (!parse_int(tok.substr(0, tok.find('/')), index) || index == 0)
          throw IOException(at_line("obj", number) + ": bad face index '" + std::string(tok) + "'");
        poly.push_back(index > 0 ? index - 1 : n + index);  // negative: relative to the end
        // v/vt/vn: a texture coordinate out of range is no error, only no colour there.
        const std::size_t slash = tok.find('/');
        long long vt = 0;
        const long long nt = static_cast<long long>(uvs.size());
        if (slash != std::string_view::npos &&
            parse_int(tok.substr(slash + 1, tok.find('/', slash + 1) - slash - 1), vt) && vt != 0)
          vt = vt > 0 ? vt - 1 : nt + vt;
        else
          vt = -1;
        poly_uvs.push_back(vt >= 0 && vt < nt ? vt : -1);
      }
      if (poly.size() < 3) ++short_faces;
      const std::size_t before = out.faces.size();
      add_polygon(out, poly, options, at_line("obj", number));
      const std::size_t added = out.faces.size() - before;
      const bool textured = std::count(poly_uvs.begin(), poly_uvs.end(), -1) == 0;
      if (textured || !out.colour.uvs.empty()) {
        const double nan = std::nan("");
        out.colour.uvs.resize(before, {UV{nan, nan}, UV{nan, nan}, UV{nan, nan}});
        for (std::size_t k = 0; k < added; ++k) {  // the fans add_polygon made
          if (!textured) {
            out.colour.uvs.push_back({UV{nan, nan}, UV{nan, nan}, UV{nan, nan}});
            continue;
          }
          out.colour.uvs.push_back({uvs[std::size_t(poly_uvs[0])],
                                    uvs[std::size_t(poly_uvs[k + 1])],
                                    uvs[std::size_t(poly_uvs[k + 2])]});
        }
      }
      if (material >= 0 || !out.colour.face_materials.empty()) {
        out.colour.face_materials.resize(before, -1);
        out.colour.face_materials.resize(before + added, material);
      }
    } else if (keyword == "l") {
      ++lines;
    } else if (keyword == "p") {
      ++points;
    }
  };
  for_each_line(bytes, [&](std::string_view line, std::size_t number) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
    if (!line.empty() && line.back() == '\\') {
      if (joined.empty()) joined_from = number;
      joined.append(line.substr(0, line.size() - 1)).push_back(' ');
      return;
    }
    if (!joined.empty()) {
      joined.append(line);
      statement(joined, joined_from);
      joined.clear();
      return;
    }
    statement(line, number);
  });
  if (!joined.empty()) statement(joined, joined_from);
  if (!out.colour.uvs.empty()) {
    const double nan = std::nan("");
    out.colour.uvs.resize(out.faces.size(), {UV{nan, nan}, UV{nan, nan}, UV{nan, nan}});
  }
  if (!out.colour.face_materials.empty()) out.colour.face_materials.resize(out.faces.size(), -1);
  if (short_faces)
    out.notes.push_back(std::to_string(short_faces) +
                        " faces with fewer than 3 vertices were skipped");
  if (lines) out.notes.push_back(std::to_string(lines) + " line elements were skipped");
  if (points) out.notes.push_back(std::to_string(points) + " point elements were skipped");
  return out;
}

RawMesh read_off(std::string_view bytes, const LoadOptions& options) {
  // Line based: a vertex is the first three numbers of its line and a face "n i1 .. in" followed
  // by optional colours, which is how COFF/NOFF/CNOFF files carry their extras. Lines are read
  // lazily: nothing is stored per line.
  struct Lines {
    std::string_view rest;
    std::size_t number = 0;
    /// The next line with content (comments cut), or false at the end.
    bool next(std::string_view& line, std::size_t& at) {
      while (!rest.empty()) {
        const std::size_t eol = rest.find('\n');
        line = rest.substr(0, eol);
        rest.remove_prefix(eol == std::string_view::npos ? rest.size() : eol + 1);
        ++number;
        line = line.substr(0, line.find('#'));
        std::string_view probe = line;
        if (!next_token(probe).empty()) {
          at = number;
          return true;
        }
      }
      return false;
    }
  };
  std::size_t content_lines = 0;
  {
    Lines count{bytes};
    std::string_view line;
    std::size_t at = 0;
    while (count.next(line, at)) ++content_lines;
  }
  Lines lines{bytes};
  std::string_view header;
  std::size_t number = 0;
  if (!lines.next(header, number)) throw IOException("off: the file has no header");
  std::string_view keyword = next_token(header);
  const std::size_t off = keyword.find("OFF");
  if (off == std::string_view::npos) throw IOException("off: the file does not start with OFF");
  if (keyword.substr(0, off).find('4') != std::string_view::npos)
    throw IOException("off: 4D OFF files are not supported");
  std::string counts_text(keyword.substr(off + 3));  // "OFF8 6 12": counts glued to the keyword
  counts_text.append(" ").append(header);
  std::string_view counts = counts_text;
  std::string_view first = next_token(counts);
  if (first.empty()) {
    if (!lines.next(counts, number))
      throw IOException("off: the vertex and face counts are missing");
    first = next_token(counts);
  }
  long long nv = 0, nf = 0;
  if (!parse_int(first, nv) || !parse_int(next_token(counts), nf) || nv < 0 || nf < 0)
    throw IOException("off: bad vertex and face counts");
  // Each vertex and face needs a line of its own: counts beyond that are lies, refused before
  // anything is allocated for them.
  if (static_cast<unsigned long long>(nv) + static_cast<unsigned long long>(nf) > content_lines)
    throw IOException("off: the header declares " + std::to_string(nv) + " vertices and " +
                      std::to_string(nf) + " faces but the file has only " +
                      std::to_string(content_lines) + " lines");
  check_declared_faces(static_cast<std::size_t>(nf), options, "off header");
  check_vertices(static_cast<std::size_t>(nv), options, "off header");
  RawMesh out;
  out.vertices.reserve(static_cast<std::size_t>(nv));
  std::string_view line;
  for (long long i = 0; i < nv; ++i) {
    if (!lines.next(line, number)) throw IOException("off: the file ends inside its vertices");
    Vec3 p;
    if (!parse_double(next_token(line), p.x) || !parse_double(next_token(line), p.y) ||
        !parse_double(next_token(line), p.z))
      throw IOException(at_line("off", number) + ": a vertex needs three numbers");
    out.vertices.push_back(p);
  }
  std::size_t short_faces = 0;
  std::vector<long long> poly;
  for (long long i = 0; i < nf; ++i) {
    if (!lines.next(line, number)) throw IOException("off: the file ends inside its faces");
    long long n = 0;
    if (!parse_int(next_token(line), n) || n < 0 || n > 1'000'000)
      throw IOException(at_line("off", number) + ": bad face size");
    poly.assign(static_cast<std::size_t>(n), 0);
    for (auto& v : poly)
      if (!parse_int(next_token(line), v))
        throw IOException(at_line("off", number) + ": a face has fewer indices than it declares");
    if (poly.size() < 3) ++short_faces;
    add_polygon(out, poly, options, at_line("off", number));
  }
  if (short_faces)
    out.notes.push_back(std::to_string(short_faces) +
                        " faces with fewer than 3 vertices were skipped");
  return out;
}

RawMesh read_stl(std::string_view bytes, const LoadOptions& options) {
  RawMesh out;
  std::uint32_t count = 0;
  if (bytes.size() >= 84) std::memcpy(&count, bytes.data() + 80, 4);
  const std::uint64_t binary_size = 84 + 50 * std::uint64_t{count};
  std::string_view text = bytes;
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  // "solid" starts many binary headers too: text is ascii only if its start has no NUL byte.
  const bool ascii = text.substr(0, 5) == "solid" &&
                     (bytes.size() < 84 || binary_size != bytes.size()) &&
                     bytes.substr(0, 1024).find('\0') == std::string_view::npos;
  if (!ascii) {
    if (bytes.size() < 84)
      throw IOException("stl: " + std::to_string(bytes.size()) +
                        " bytes is too short for a binary STL header (84 bytes)");
    if (binary_size > bytes.size())
      throw IOException("stl: binary header declares " + std::to_string(count) + " triangles (" +
                        std::to_string(binary_size) + " bytes) but the file has " +
                        std::to_string(bytes.size()) + " bytes");
    check_declared_faces(count, options, "stl header");
    check_vertices(3 * std::size_t{count}, options, "stl header");
    if (binary_size < bytes.size())
      out.notes.push_back(std::to_string(bytes.size() - binary_size) +
                          " bytes after the last triangle were ignored");
    out.vertices.reserve(3 * std::size_t{count});
    out.faces.reserve(count);
    const char* p = bytes.data() + 84;
    for (std::uint32_t t = 0; t < count; ++t, p += 50) {
      for (int k = 0; k < 3; ++k) {
        float xyz[3];
        std::memcpy(xyz, p + 12 + 12 * k, 12);  // after the facet normal
        out.vertices.push_back({xyz[0], xyz[1], xyz[2]});
      }
      const int base = static_cast<int>(3 * t);
      out.faces.push_back({base, base + 1, base + 2});
    }
    return out;
  }
  std::vector<long long> poly;
  std::size_t short_facets = 0;
  bool in_facet = false;
  for (std::string_view tok = next_token(text); !tok.empty(); tok = next_token(text)) {
    if (tok == "facet") {
      in_facet = true;
      poly.clear();
    } else if (tok == "vertex") {
      Vec3 v;
      if (!parse_double(next_token(text), v.x) || !parse_double(next_token(text), v.y) ||
          !parse_double(next_token(text), v.z))
        throw IOException("stl: a vertex needs three numbers");
      if (!in_facet) throw IOException("stl: a vertex outside a facet");
      poly.push_back(static_cast<long long>(out.vertices.size()));
      check_vertices(out.vertices.size() + 1, options, "stl");
      out.vertices.push_back(v);
    } else if (tok == "endfacet") {
      if (poly.size() < 3) ++short_facets;
      add_polygon(out, poly, options, "stl");
      in_facet = false;
    }
  }
  if (in_facet) throw IOException("stl: the file ends inside a facet");
  if (short_facets)
    out.notes.push_back(std::to_string(short_facets) +
                        " facets with fewer than 3 vertices were skipped");
  return out;
}

}  // namespace papernet::detail
