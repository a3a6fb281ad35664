#include "server/static_files.h"

#include <httplib.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace papernet::server {

std::string mount_web_root(httplib::Server& http,
                           const std::function<const char*(const char*)>& getenv) {
  const char* dir = getenv("PAPERNET_WEB_ROOT");
  if (dir == nullptr || *dir == '\0') return "";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec) || !http.set_mount_point("/", dir))
    throw std::invalid_argument(std::string("PAPERNET_WEB_ROOT: '") + dir + "' is not a directory");
  // The page and its bundle are rebuilt with the binary; do not let browsers keep stale copies.
  http.set_file_request_handler([](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-cache");
  });
  return dir;
}

}  // namespace papernet::server
