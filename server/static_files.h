#pragma once

#include <string>

namespace httplib {
class Server;
}

namespace papernet::server {

/// Serves the web demo (the built clients/web bundle) at `/` from `dir` (ServerConfig::web_root,
/// `--web-root` / PAPERNET_WEB_ROOT): GET /, /index.html, /assets/... answer with its files
/// (types by extension); API routes are unaffected unless the directory holds files of the same
/// names. An empty `dir` serves nothing.
/// \throw std::invalid_argument naming `dir` when it is not a directory.
void mount_web_root(httplib::Server& http, const std::string& dir);

}  // namespace papernet::server
