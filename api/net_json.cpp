#include "api/net_json.h"

#include <string>

#include "core/errors.h"

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
  json repairs = json::array(), pieces = json::array();
  for (const NetRepair& r : doc.repairs)
    repairs.push_back({{"code", r.code}, {"count", r.count}, {"message", r.message}});
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
  if (doc.intermediate)
    out["level"] = {{"kind", "intermediate"},
                    {"faces", doc.mesh.faces.size()},
                    {"input_faces", doc.input.faces}};
  return out;
}

std::string write_net_json(const NetDocument& doc, int indent) {
  return net_to_json(doc).dump(indent);
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
    const auto& m = field(j, "metrics", "the document");
    doc.metrics.faces = field(m, "faces", "metrics").get<std::size_t>();
    if (!field(m, "coverage", "metrics").is_null())
      doc.metrics.coverage = m["coverage"].get<double>();
    if (!field(m, "aspect_ratio", "metrics").is_null())
      doc.metrics.aspect_ratio = m["aspect_ratio"].get<double>();
    doc.metrics.hausdorff = field(m, "hausdorff", "metrics").get<double>();
    doc.metrics.overlaps = field(m, "overlaps", "metrics").get<std::size_t>();
    doc.metrics.seconds = field(m, "seconds", "metrics").get<double>();
    return doc;
  } catch (const nlohmann::json::exception& e) {
    throw IOException(std::string("net JSON: ") + e.what());
  }
}

}  // namespace papernet
