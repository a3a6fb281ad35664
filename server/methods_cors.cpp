// The methods each path of the API takes, and CORS (server/internal/methods_cors.h).
#include "server/internal/methods_cors.h"

#include <regex>

namespace papernet::server {

std::string allowed_methods(const std::string& path) {
  static const std::regex job("^/v1/jobs/[^/]+$");
  static const std::regex job_get(
      "^/v1/jobs/[^/]+/(events|net\\.json|net\\.svg|net\\.pdf|mesh\\.glb|pages/[0-9]{1,6}|"
      "textures/[0-9]{1,6})$");
  if (path == "/v1/jobs") return "GET, HEAD, POST";
  if (std::regex_match(path, job)) return "GET, HEAD, DELETE";
  if (path == "/healthz" || path == "/readyz" || path == "/metrics" || path == "/v1/openapi.json" ||
      std::regex_match(path, job_get))
    return "GET, HEAD";
  return "";
}

bool method_allowed(const std::string& allowed, const std::string& method) {
  std::size_t from = 0;
  while (from < allowed.size()) {
    std::size_t to = allowed.find(", ", from);
    if (to == std::string::npos) to = allowed.size();
    if (allowed.compare(from, to - from, method) == 0) return true;
    from = to + 2;
  }
  return false;
}

CorsAnswer answer_cors(const ServerConfig& config, const std::string& allowed,
                       const std::string& method, const std::optional<std::string>& origin,
                       bool requests_method) {
  CorsAnswer out;
  if (config.cors_origins.empty()) return out;
  // What Access-Control-Allow-Origin says to this Origin ("" = nothing: none, or one not listed).
  std::string allow;
  if (origin && !origin->empty())
    for (const std::string& o : config.cors_origins)
      if (o == "*" || o == *origin) {
        allow = o;
        break;
      }
  if (allow != "*") out.headers.emplace_back("Vary", "Origin");  // one answer per origin cached
  if (!allow.empty()) {
    out.headers.emplace_back("Access-Control-Allow-Origin", allow);
    out.headers.emplace_back("Access-Control-Expose-Headers",
                             "Location, Retry-After, X-Papernet-Level, Allow, "
                             "Idempotent-Replayed, Content-Disposition");
  }
  if (method != "OPTIONS" || !origin || !requests_method) return out;
  out.preflight = true;
  if (allow.empty()) {
    out.refused = make_problem("origin_not_allowed",
                               "the origin " + origin->substr(0, 128) +
                                   " may not call this API from a browser (see --cors-origins)");
    return out;
  }
  out.headers.emplace_back("Access-Control-Allow-Methods", allowed);
  out.headers.emplace_back("Access-Control-Allow-Headers",
                           "Authorization, Content-Type, Idempotency-Key, Last-Event-ID");
  out.headers.emplace_back("Access-Control-Max-Age", "600");
  return out;
}

}  // namespace papernet::server
