#pragma once

#include <functional>
#include <string>

namespace httplib {
class Server;
}

namespace papernet::server {

/// Serves the web demo (the built clients/web bundle) at `/` when the environment variable
/// PAPERNET_WEB_ROOT names a directory: GET /, /index.html, /assets/... answer with its files
/// (types by extension); API routes are unaffected unless the directory holds files of the same
/// names. Returns the directory served, or "" when none is configured.
/// \throw std::invalid_argument when PAPERNET_WEB_ROOT is set but is not a directory.
std::string mount_web_root(
    httplib::Server& http, const std::function<const char*(const char*)>& getenv =
                               [](const char* n) { return std::getenv(n); });

}  // namespace papernet::server
