#pragma once

#include <string_view>

namespace papernet {

/// The OpenAPI 3 description of the /v1 HTTP API (api/openapi.json, embedded at build time).
std::string_view openapi_document();

}  // namespace papernet
