#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "api/options.h"
#include "server/job.h"

namespace httplib {
struct Request;
}

namespace papernet::server {

/// One part of a multipart/form-data upload.
struct UploadPart {
  std::string name;  ///< form field: "mesh", "buffers", "options"
  std::string filename;
  std::string content_type;
  std::string content;
};

/// A POST /v1/jobs request with the HTTP library taken away, so parsing is testable without
/// sockets.
struct UploadRequest {
  std::string content_type;  ///< the request's Content-Type header ("" when absent)
  std::string body;          ///< raw body (empty for multipart)
  bool multipart = false;
  std::vector<UploadPart> parts;
  std::multimap<std::string, std::string> query;
};

struct ParsedUpload {
  JobInput input;
  JobOptions options;
};

/// The parts of a request parse_upload() looks at, taken from an HTTP request that httplib has
/// read whole (and, for multipart/form-data, split into parts). The route itself streams the
/// body through a bounded reader instead (http_api.cpp); this buffered form serves the upload
/// fuzz target, which drives httplib's own request and multipart parsing from memory.
UploadRequest upload_request_of(const httplib::Request& req);

/// Turns a request into a job's input and options: format from the `format` query parameter,
/// the part's Content-Type or file name, the request's Content-Type, or else the content
/// itself (core's sniff_format).
/// \throw ApiError (missing_mesh, malformed_request, unsupported_format) or InvalidOptionException.
ParsedUpload parse_upload(UploadRequest request, const OptionsLimits& limits);

/// The format a media type names; Unknown for generic types (octet-stream, text/plain, none).
/// \throw ApiError unsupported_format for a media type that is clearly no mesh we read.
MeshFormat format_from_media_type(std::string_view media_type);

/// The media type a client should send for a format.
std::string media_type_of(MeshFormat format);

}  // namespace papernet::server
