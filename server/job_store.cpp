#include "server/job_store.h"

#include <filesystem>

#include "server/pg_store.h"
#include "server/sqlite_store.h"

namespace papernet::server {

bool is_postgres_url(const std::string& spec) {
  return spec.rfind("postgres://", 0) == 0 || spec.rfind("postgresql://", 0) == 0;
}

std::unique_ptr<JobStore> open_job_store(const std::string& spec, const std::string& data_dir,
                                         std::size_t connections) {
  if (is_postgres_url(spec)) return std::make_unique<PgJobStore>(spec, connections);
  if (spec != "sqlite")
    throw StoreError("job store: '" + redact_store_url(spec) +
                     "' is neither sqlite nor a postgres:// URL");
  try {
    std::filesystem::create_directories(data_dir);
  } catch (const std::filesystem::filesystem_error& e) {
    throw StoreError("job store: cannot create '" + data_dir + "': " + e.code().message());
  }
  return std::make_unique<SqliteJobStore>(
      (std::filesystem::path(data_dir) / "papernet.sqlite").string());
}

std::string redact_store_url(const std::string& url) {
  // scheme://user:password@host...: the password is what lies between the first ':' after the
  // scheme and the last '@' before the path.
  // A password=... query parameter is cut out too.
  std::string out = url;
  if (const auto query = out.find("password="); query != std::string::npos) {
    const auto end = out.find('&', query);
    out = out.substr(0, query + 9) + "***" + (end == std::string::npos ? "" : out.substr(end));
  }
  const auto scheme = out.find("://");
  if (scheme == std::string::npos) return out;
  const auto authority = scheme + 3;
  const auto path = out.find_first_of("/?", authority);
  const auto at = out.rfind('@', path);
  if (at == std::string::npos || at < authority) return out;
  const auto colon = out.find(':', authority);
  if (colon == std::string::npos || colon > at) return out;
  return out.substr(0, colon + 1) + "***" + out.substr(at);
}

}  // namespace papernet::server
