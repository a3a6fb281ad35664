// Private to server/: the methods each path of the API takes, and the CORS answer to a browser
// (docs/security.md), apart from HTTP: strings in, headers and problems out.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "server/config.h"
#include "server/problem.h"

namespace papernet::server {

/// The methods a path of the API takes, "GET, HEAD, POST" ("" for a path that is not the
/// API's). HEAD goes with GET.
std::string allowed_methods(const std::string& path);

/// Whether `method` is one of `allowed` (allowed_methods').
bool method_allowed(const std::string& allowed, const std::string& method);

/// What a request's CORS headers get in answer (ServerConfig::cors_origins).
struct CorsAnswer {
  std::vector<std::pair<std::string, std::string>> headers;  ///< added to the answer
  /// A preflight (OPTIONS with Origin and Access-Control-Request-Method), answered with the
  /// headers: 204, or `refused` (origin_not_allowed) for an origin not listed.
  bool preflight = false;
  std::optional<Problem> refused;
};

/// The CORS answer to a request of `method` with the Origin header `origin` (std::nullopt: none)
/// and, for a preflight, Access-Control-Request-Method, on a path that takes `allowed`. Without
/// `config.cors_origins`: nothing.
CorsAnswer answer_cors(const ServerConfig& config, const std::string& allowed,
                       const std::string& method, const std::optional<std::string>& origin,
                       bool requests_method);

}  // namespace papernet::server
