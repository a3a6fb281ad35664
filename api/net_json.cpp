#include "api/net_json.h"

#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"
#include "core/io/json_text.h"

namespace papernet {

namespace {

constexpr const char* kFormat = "papernet.net/2";

nlohmann::json optional_number(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

const nlohmann::json& field(const nlohmann::json& j, const char* name, const std::string& where) {
  if (!j.is_object() || !j.contains(name))
    throw IOException("net JSON: " + where + " has no field '" + name + "'");
  return j.at(name);
}

// A face's corners as [[..], [..], [..]], or null when any value is not finite (no data).
template <std::size_t N>
nlohmann::json corners_json(const std::array<std::array<double, N>, 3>& corners) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& c : corners) {
    nlohmann::json values = nlohmann::json::array();
    for (double x : c) {
      if (!std::isfinite(x)) return nullptr;
      values.push_back(x);
    }
    out.push_back(std::move(values));
  }
  return out;
}

template <std::size_t N>
std::array<std::array<double, N>, 3> corners_from(const nlohmann::json& j) {
  std::array<std::array<double, N>, 3> out;
  for (auto& c : out) c.fill(std::numeric_limits<double>::quiet_NaN());
  if (j.is_null()) return out;
  if (!j.is_array() || j.size() != 3) throw IOException("net JSON: a face needs three corners");
  for (std::size_t k = 0; k < 3; ++k) {
    if (!j[k].is_array() || j[k].size() != N)
      throw IOException(std::string("net JSON: a corner needs ") + std::to_string(N) + " numbers");
    for (std::size_t i = 0; i < N; ++i) out[k][i] = j[k][i].get<double>();
  }
  return out;
}

// `mesh.uvs`, `mesh.colors`, `mesh.face_materials`, `materials` and `textures`, written only
// when the document has colour (docs/colour.md).
void colour_to_json(const MeshColour& c, nlohmann::json& out) {
  using nlohmann::json;
  if (c.empty() && c.materials.empty()) return;
  json& mesh = out["mesh"];
  if (!c.uvs.empty()) {
    json uvs = json::array();
    for (const auto& f : c.uvs) uvs.push_back(corners_json(f));
    mesh["uvs"] = std::move(uvs);
  }
  if (!c.colours.empty()) {
    json colours = json::array();
    for (const auto& f : c.colours) colours.push_back(corners_json(f));
    mesh["colors"] = std::move(colours);
  }
  if (!c.face_materials.empty()) mesh["face_materials"] = c.face_materials;
  json materials = json::array(), textures = json::array();
  for (const Material& m : c.materials)
    materials.push_back({{"name", m.name},
                         {"base_color", m.base_color},
                         {"texture", m.texture >= 0 ? json(m.texture) : json(nullptr)},
                         {"alpha_mode", alpha_mode_name(m.alpha_mode)},
                         {"alpha_cutoff", m.alpha_cutoff}});
  for (const Texture& t : c.textures)
    textures.push_back({{"name", t.name},
                        {"mime_type", t.mime_type},
                        {"width", t.width},
                        {"height", t.height},
                        {"sampler",
                         {{"wrap_s", t.sampler.wrap_s},
                          {"wrap_t", t.sampler.wrap_t},
                          {"mag_filter", t.sampler.mag_filter},
                          {"min_filter", t.sampler.min_filter}}}});
  out["materials"] = std::move(materials);
  out["textures"] = std::move(textures);
}

void colour_from_json(const nlohmann::json& j, const nlohmann::json& mesh, std::size_t faces,
                      MeshColour& c) {
  const auto count = [faces](const nlohmann::json& a, const char* name) {
    if (!a.is_array() || a.size() != faces)
      throw IOException(std::string("net JSON: mesh.") + name +
                        " does not have one entry per face");
  };
  if (mesh.contains("uvs")) {
    count(mesh["uvs"], "uvs");
    for (const auto& f : mesh["uvs"]) c.uvs.push_back(corners_from<2>(f));
  }
  if (mesh.contains("colors")) {
    count(mesh["colors"], "colors");
    for (const auto& f : mesh["colors"]) c.colours.push_back(corners_from<4>(f));
  }
  if (mesh.contains("face_materials")) {
    count(mesh["face_materials"], "face_materials");
    c.face_materials = mesh["face_materials"].get<std::vector<int>>();
  }
  if (j.contains("textures"))
    for (const auto& t : j["textures"]) {
      Texture texture;
      texture.name = field(t, "name", "a texture").get<std::string>();
      texture.mime_type = field(t, "mime_type", "a texture").get<std::string>();
      texture.width = field(t, "width", "a texture").get<int>();
      texture.height = field(t, "height", "a texture").get<int>();
      if (t.contains("sampler")) {
        const auto& s = t["sampler"];
        texture.sampler = {s.value("wrap_s", 10497), s.value("wrap_t", 10497),
                           s.value("mag_filter", 0), s.value("min_filter", 0)};
      }
      c.textures.push_back(std::move(texture));
    }
  if (j.contains("materials"))
    for (const auto& m : j["materials"]) {
      Material material;
      material.name = field(m, "name", "a material").get<std::string>();
      material.base_color = field(m, "base_color", "a material").get<RGBA>();
      const auto& t = field(m, "texture", "a material");
      material.texture = t.is_null() ? -1 : t.get<int>();
      const std::string mode = m.value("alpha_mode", std::string("OPAQUE"));
      if (mode == "MASK")
        material.alpha_mode = AlphaMode::Mask;
      else if (mode == "BLEND")
        material.alpha_mode = AlphaMode::Blend;
      else if (mode != "OPAQUE")
        throw IOException("net JSON: a material's alpha_mode is '" + mode +
                          "', not OPAQUE, MASK or BLEND");
      material.alpha_cutoff = m.value("alpha_cutoff", 0.5);
      if (material.texture >= int(c.textures.size()) || material.texture < -1)
        throw IOException(std::string("net JSON: a material names texture ") +
                          std::to_string(material.texture) + " of " +
                          std::to_string(c.textures.size()));
      c.materials.push_back(std::move(material));
    }
  for (int m : c.face_materials)
    if (m < -1 || m >= int(c.materials.size()))
      throw IOException(std::string("net JSON: a face names material ") + std::to_string(m) +
                        " of " + std::to_string(c.materials.size()));
}

nlohmann::json print_to_json(const NetPrint& print) {
  using nlohmann::json;
  json placements = json::array();
  for (const PiecePlacement& p : print.placements)
    placements.push_back({{"piece", p.piece}, {"page", p.page}, {"transform", p.transform}});
  json out{{"paper", print.paper},
           {"page_size_mm", {print.page_width_mm, print.page_height_mm}},
           {"margin_mm", print.margin_mm},
           {"mm_per_unit", print.mm_per_unit},
           {"pages", print.pages},
           {"layout", print.layout},
           {"placements", std::move(placements)}};
  if (!print.title.empty()) out["title"] = print.title;
  if (!print.tiles.empty()) {
    json tiles = json::array();
    for (const PageWindow& t : print.tiles)
      tiles.push_back({{"page", t.page}, {"window_mm", t.window_mm}});
    out["tiles"] = std::move(tiles);
  }
  if (print.overview_page >= 0) {
    out["overview_page"] = print.overview_page;
    out["overview_pages"] = print.overview_pages;
  }
  return out;
}

NetPrint print_from_json(const nlohmann::json& j, std::size_t pieces) {
  NetPrint print;
  print.paper = field(j, "paper", "print").get<std::string>();
  const auto size = field(j, "page_size_mm", "print").get<std::array<double, 2>>();
  print.page_width_mm = size[0];
  print.page_height_mm = size[1];
  print.margin_mm = j.value("margin_mm", 0.0);
  print.mm_per_unit = field(j, "mm_per_unit", "print").get<double>();
  print.pages = field(j, "pages", "print").get<int>();
  print.layout = field(j, "layout", "print").get<std::string>();
  if (j.contains("title")) print.title = j["title"].get<std::string>();
  for (const auto& p : field(j, "placements", "print")) {
    PiecePlacement placed;
    placed.piece = field(p, "piece", "a placement").get<int>();
    placed.page = field(p, "page", "a placement").get<int>();
    placed.transform = field(p, "transform", "a placement").get<std::array<double, 6>>();
    if (placed.piece < 0 || static_cast<std::size_t>(placed.piece) >= pieces || placed.page < -1 ||
        placed.page >= print.pages)
      throw IOException("net JSON: a placement names piece " + std::to_string(placed.piece) +
                        " of " + std::to_string(pieces) + " on page " +
                        std::to_string(placed.page) + " of " + std::to_string(print.pages));
    print.placements.push_back(placed);
  }
  if (print.placements.size() != pieces)
    throw IOException("net JSON: " + std::to_string(print.placements.size()) + " placements for " +
                      std::to_string(pieces) + " pieces");
  if (j.contains("tiles"))
    for (const auto& t : j["tiles"])
      print.tiles.push_back({field(t, "page", "a tile").get<int>(),
                             field(t, "window_mm", "a tile").get<std::array<double, 4>>()});
  print.overview_page = j.value("overview_page", -1);
  if (print.overview_page < -1 || print.overview_page >= print.pages)
    throw IOException("net JSON: the overview is page " + std::to_string(print.overview_page) +
                      " of " + std::to_string(print.pages));
  print.overview_pages = j.value("overview_pages", print.overview_page >= 0 ? 1 : 0);
  if (print.overview_pages < (print.overview_page >= 0 ? 1 : 0) ||
      (print.overview_page < 0 && print.overview_pages != 0) ||
      print.overview_page + print.overview_pages > print.pages)
    throw IOException("net JSON: " + std::to_string(print.overview_pages) +
                      " overview pages from page " + std::to_string(print.overview_page) + " of " +
                      std::to_string(print.pages));
  return print;
}

}  // namespace

nlohmann::json net_to_json(const NetDocument& doc) {
  using nlohmann::json;
  json vertices = json::array(), faces = json::array(), net_faces = json::array();
  for (const Vec3& v : doc.mesh.vertices) vertices.push_back({v.x, v.y, v.z});
  for (const auto& f : doc.mesh.faces) faces.push_back({f[0], f[1], f[2]});
  for (std::size_t i = 0; i < doc.net.points.size(); ++i) {
    const auto& p = doc.net.points[i];
    json points = json::array();
    for (const Vec2& q : p) points.push_back({q.x, q.y});
    net_faces.push_back({{"piece", i < doc.piece.size() ? doc.piece[i] : 0},
                         {"parent", i < doc.net.parent.size() ? doc.net.parent[i] : -1},
                         {"points", std::move(points)}});
  }
  json repairs = json::array(), warnings = json::array(), pieces = json::array();
  for (const NetRepair& r : doc.repairs)
    repairs.push_back({{"code", r.code}, {"count", r.count}, {"message", r.message}});
  for (const NetRepair& r : doc.warnings)
    warnings.push_back({{"code", r.code}, {"count", r.count}, {"message", r.message}});
  for (const NetPiece& p : doc.pieces)
    pieces.push_back({{"component", p.component},
                      {"result", p.result},
                      {"faces", p.faces},
                      {"hausdorff", p.hausdorff}});
  json out{
      {"format", kFormat},
      {"result", doc.result},
      {"strategy", doc.strategy},
      {"input",
       {{"vertices", doc.input.vertices},
        {"faces", doc.input.faces},
        {"components", doc.input.components},
        {"genus", doc.input.genus},
        {"boundaries", doc.input.boundaries}}},
      {"repairs", std::move(repairs)},
      {"detail", {{"mode", doc.detail.mode}, {"faces", doc.detail.faces}}},
      {"warnings", std::move(warnings)},
      {"pieces", std::move(pieces)},
      {"mesh", {{"vertices", std::move(vertices)}, {"faces", std::move(faces)}}},
      {"net", {{"faces", std::move(net_faces)}}},
      {"metrics",
       {{"faces", doc.metrics.faces},
        {"coverage", optional_number(doc.metrics.coverage)},
        {"aspect_ratio", optional_number(doc.metrics.aspect_ratio)},
        {"hausdorff", doc.metrics.hausdorff},
        {"overlaps", doc.metrics.overlaps},
        {"seconds", doc.metrics.seconds}}},
  };
  colour_to_json(doc.colour, out);
  if (doc.print) out["print"] = print_to_json(*doc.print);
  if (doc.intermediate)
    out["level"] = {{"kind", "intermediate"},
                    {"faces", doc.mesh.faces.size()},
                    {"input_faces", doc.input.faces}};
  return out;
}

std::string write_net_json(const NetDocument& doc, int indent) {
  return json_text(net_to_json(doc), indent);
}

NetDocument read_net_json(std::string_view text) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded()) throw IOException("net JSON: not valid JSON");
  try {
    if (field(j, "format", "the document") != kFormat)
      throw IOException("net JSON: format is not '" + std::string(kFormat) + "'");
    NetDocument doc;
    doc.result = field(j, "result", "the document").get<std::string>();
    doc.strategy = field(j, "strategy", "the document").get<std::string>();
    const auto& in = field(j, "input", "the document");
    doc.input.vertices = field(in, "vertices", "input").get<std::size_t>();
    doc.input.faces = field(in, "faces", "input").get<std::size_t>();
    doc.input.components = field(in, "components", "input").get<std::size_t>();
    doc.input.genus = field(in, "genus", "input").get<int>();
    doc.input.boundaries = field(in, "boundaries", "input").get<std::size_t>();
    const auto& mesh = field(j, "mesh", "the document");
    for (const auto& v : field(mesh, "vertices", "mesh"))
      doc.mesh.vertices.push_back(
          {v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>()});
    for (const auto& f : field(mesh, "faces", "mesh"))
      doc.mesh.faces.push_back({f.at(0).get<int>(), f.at(1).get<int>(), f.at(2).get<int>()});
    for (const auto& r : field(j, "repairs", "the document"))
      doc.repairs.push_back({field(r, "code", "a repair").get<std::string>(),
                             field(r, "count", "a repair").get<std::size_t>(),
                             field(r, "message", "a repair").get<std::string>()});
    if (const auto d = j.find("detail"); d != j.end() && d->is_object()) {
      doc.detail.mode = field(*d, "mode", "detail").get<std::string>();
      doc.detail.faces = field(*d, "faces", "detail").get<std::size_t>();
    }
    if (const auto w = j.find("warnings"); w != j.end())
      for (const auto& r : *w)
        doc.warnings.push_back({field(r, "code", "a warning").get<std::string>(),
                                field(r, "count", "a warning").get<std::size_t>(),
                                field(r, "message", "a warning").get<std::string>()});
    for (const auto& p : field(j, "pieces", "the document"))
      doc.pieces.push_back({field(p, "component", "a piece").get<std::size_t>(),
                            field(p, "result", "a piece").get<std::string>(),
                            field(p, "faces", "a piece").get<std::size_t>(),
                            field(p, "hausdorff", "a piece").get<double>()});
    for (const auto& f : field(field(j, "net", "the document"), "faces", "net")) {
      const int piece = field(f, "piece", "a net face").get<int>();
      if (piece < 0 || static_cast<std::size_t>(piece) >= doc.pieces.size())
        throw IOException("net JSON: a net face names piece " + std::to_string(piece) + " of " +
                          std::to_string(doc.pieces.size()));
      doc.piece.push_back(piece);
      doc.net.parent.push_back(field(f, "parent", "a net face").get<int>());
      const auto& p = field(f, "points", "a net face");
      std::array<Vec2, 3> t;
      for (int k = 0; k < 3; ++k) t[k] = {p.at(k).at(0).get<double>(), p.at(k).at(1).get<double>()};
      doc.net.points.push_back(t);
    }
    if (doc.net.points.size() != doc.mesh.faces.size())
      throw IOException("net JSON: " + std::to_string(doc.net.points.size()) + " net faces for " +
                        std::to_string(doc.mesh.faces.size()) + " mesh faces");
    colour_from_json(j, mesh, doc.mesh.faces.size(), doc.colour);
    const auto& m = field(j, "metrics", "the document");
    doc.metrics.faces = field(m, "faces", "metrics").get<std::size_t>();
    if (!field(m, "coverage", "metrics").is_null())
      doc.metrics.coverage = m["coverage"].get<double>();
    if (!field(m, "aspect_ratio", "metrics").is_null())
      doc.metrics.aspect_ratio = m["aspect_ratio"].get<double>();
    doc.metrics.hausdorff = field(m, "hausdorff", "metrics").get<double>();
    doc.metrics.overlaps = field(m, "overlaps", "metrics").get<std::size_t>();
    doc.metrics.seconds = field(m, "seconds", "metrics").get<double>();
    if (j.contains("print")) doc.print = print_from_json(j["print"], doc.pieces.size());
    return doc;
  } catch (const nlohmann::json::exception& e) {
    throw IOException(std::string("net JSON: ") + e.what());
  }
}

}  // namespace papernet
