#include "server/upload.h"

#include <httplib.h>

#include <algorithm>
#include <cctype>

#include "core/ascii.h"
#include "server/problem.h"

namespace papernet::server {
namespace {

// A .gltf's buffers are named by relative URIs; a name is only a key into the upload, never a
// path on the server, but names that look like paths are refused to keep that obvious.
bool plain_file_name(std::string_view name) {
  if (name.empty() || name.size() > 255 || name.front() == '/' || name.front() == '.') return false;
  if (name.find("..") != std::string_view::npos || name.find('\\') != std::string_view::npos)
    return false;
  return std::none_of(name.begin(), name.end(),
                      [](unsigned char c) { return c < 0x20 || c == 0x7f; });
}

MeshFormat format_parameter(const std::string& value) {
  const MeshFormat f = format_from_extension("x." + ascii_lower(value));
  if (f == MeshFormat::Unknown)
    throw ApiError("unsupported_format",
                   "format '" + value + "' is not one of glb, gltf, drc, obj, off, ply, stl");
  return f;
}

}  // namespace

MeshFormat format_from_media_type(std::string_view media_type) {
  std::string type = ascii_lower(media_type.substr(0, media_type.find(';')));
  type.erase(
      std::remove_if(type.begin(), type.end(), [](unsigned char c) { return std::isspace(c); }),
      type.end());
  if (type.empty() || type == "application/octet-stream" || type == "text/plain")
    return MeshFormat::Unknown;
  if (type == "model/gltf-binary") return MeshFormat::Glb;
  if (type == "model/gltf+json" || type == "application/json") return MeshFormat::Gltf;
  if (type == "model/obj" || type == "text/x-obj" || type == "application/x-tgif")
    return MeshFormat::Obj;
  if (type == "model/stl" || type == "model/x.stl-binary" || type == "model/x.stl-ascii" ||
      type == "application/sla" || type == "application/vnd.ms-pki.stl")
    return MeshFormat::Stl;
  if (type == "model/x-ply" || type == "application/x-ply" || type == "application/ply" ||
      type == "model/ply")
    return MeshFormat::Ply;
  if (type == "model/x-off" || type == "application/x-off" || type == "model/off")
    return MeshFormat::Off;
  if (type == "model/x-draco" || type == "application/x-draco" || type == "model/vnd.google.draco")
    return MeshFormat::Draco;
  throw ApiError("unsupported_format",
                 "Content-Type '" + std::string(media_type) +
                     "' is no mesh format papernet reads (model/gltf-binary, model/gltf+json, "
                     "model/x-draco, model/obj, model/x-off, model/x-ply, model/stl, or "
                     "application/octet-stream to have it sniffed)");
}

std::string media_type_of(MeshFormat format) {
  switch (format) {
    case MeshFormat::Glb:
      return "model/gltf-binary";
    case MeshFormat::Gltf:
      return "model/gltf+json";
    case MeshFormat::Obj:
      return "model/obj";
    case MeshFormat::Off:
      return "model/x-off";
    case MeshFormat::Ply:
      return "model/x-ply";
    case MeshFormat::Stl:
      return "model/stl";
    case MeshFormat::Draco:
      return "model/x-draco";
    case MeshFormat::Unknown:
      break;
  }
  return "application/octet-stream";
}

UploadRequest upload_request_of(const httplib::Request& req) {
  UploadRequest up;
  up.content_type = req.get_header_value("Content-Type");
  up.query = {req.params.begin(), req.params.end()};
  up.multipart = req.is_multipart_form_data();
  if (up.multipart) {
    for (const auto& [name, part] : req.files)
      up.parts.push_back({part.name, part.filename, part.content_type, part.content});
  } else {
    up.body = req.body;
  }
  return up;
}

ParsedUpload parse_upload(UploadRequest request, const OptionsLimits& limits) {
  ParsedUpload out;
  MeshFormat format = MeshFormat::Unknown;
  if (auto it = request.query.find("format"); it != request.query.end()) {
    format = format_parameter(it->second);
    request.query.erase(it);
  }
  bool options_part = false;
  if (request.multipart) {
    bool mesh_seen = false;
    for (UploadPart& part : request.parts) {
      if (part.name == "mesh") {
        if (mesh_seen) throw ApiError("malformed_request", "more than one 'mesh' part");
        mesh_seen = true;
        out.input.mesh = std::move(part.content);
        if (format == MeshFormat::Unknown) format = format_from_media_type(part.content_type);
        if (format == MeshFormat::Unknown) format = format_from_extension(part.filename);
      } else if (part.name == "buffers") {
        if (!plain_file_name(part.filename))
          throw ApiError("malformed_request",
                         "a 'buffers' part needs the file name its glTF uses (a plain relative "
                         "name), got '" +
                             part.filename + "'");
        if (!out.input.external_files.emplace(part.filename, std::move(part.content)).second)
          throw ApiError("malformed_request", "two 'buffers' parts named '" + part.filename + "'");
      } else if (part.name == "options") {
        if (options_part) throw ApiError("malformed_request", "more than one 'options' part");
        options_part = true;
        out.options = parse_options_json(part.content, limits);
      } else {
        throw ApiError("malformed_request", "unexpected form part '" + part.name +
                                                "' (expected mesh, buffers, options)");
      }
    }
    if (!mesh_seen) throw ApiError("missing_mesh", "the multipart upload has no 'mesh' part");
  } else {
    out.input.mesh = std::move(request.body);
    if (format == MeshFormat::Unknown) format = format_from_media_type(request.content_type);
  }
  if (options_part && !request.query.empty())
    throw InvalidOptionException(
        "conflicting_options", request.query.begin()->first,
        "give options either as query parameters or as the 'options' part, not "
        "both");
  if (!options_part) out.options = parse_options_query(request.query, limits);
  if (out.input.mesh.empty()) throw ApiError("missing_mesh", "the request carries no mesh");
  const MeshFormat sniffed = sniff_format(out.input.mesh);
  // The bytes name their format surely only by a signature (GLB, Draco, PLY, OFF, glTF's JSON,
  // a binary STL's size); OBJ and ASCII STL are guessed, and a guess contradicts nothing.
  const bool signed_bytes = sniffed != MeshFormat::Unknown && sniffed != MeshFormat::Obj &&
                            !(sniffed == MeshFormat::Stl && out.input.mesh.starts_with("solid"));
  if (format != MeshFormat::Unknown && signed_bytes && sniffed != format)
    throw ApiError("unsupported_format",
                   "the body is " + format_name(sniffed) + " by its content, not the declared " +
                       format_name(format) + " (" + media_type_of(format) + ")");
  if (format == MeshFormat::Unknown) format = sniffed;
  if (format == MeshFormat::Unknown)
    throw ApiError("unsupported_format",
                   "cannot tell the mesh format from the content; send a Content-Type such as "
                   "model/gltf-binary or model/obj, or add ?format=obj");
  out.input.format = format;
  return out;
}

}  // namespace papernet::server
