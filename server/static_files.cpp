#include "server/static_files.h"

#include <httplib.h>

#include <filesystem>
#include <stdexcept>

namespace papernet::server {

void mount_web_root(httplib::Server& http, const std::string& dir) {
  if (dir.empty()) return;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec) || !http.set_mount_point("/", dir))
    throw std::invalid_argument("web root '" + dir + "' is not a directory");
  // The page and its bundle are rebuilt with the binary; do not let browsers keep stale copies.
  http.set_file_request_handler([](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-cache");
  });
}

}  // namespace papernet::server
