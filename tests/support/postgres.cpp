#include "tests/support/postgres.h"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>

#include "server/pg.h"
#include "server/pg_store.h"
#include "server/sqlite_store.h"

namespace papernet::test {
namespace {

constexpr int kNotInstalled = 77;  // scripts/test-postgres.sh: no PostgreSQL binaries

namespace fs = std::filesystem;

std::string file_text(const fs::path& path) {
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text;
}

std::string url_parameter(const std::string& url, const std::string& name) {
  const auto at = url.find(name + "=");
  if (at == std::string::npos) return "";
  const auto from = at + name.size() + 1;
  return url.substr(from, url.find('&', from) - from);
}

}  // namespace

std::vector<std::string>& server_store_flags() {
  static std::vector<std::string> flags;
  return flags;
}

int PostgresServer::script(const std::string& command, std::string* output) const {
  const std::string line =
      "bash " PAPERNET_TEST_POSTGRES_SCRIPT " " + command + " '" + dir_ + "' 2>&1";
  FILE* p = popen(line.c_str(), "r");
  std::string text;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) text.append(buf, n);
  const int status = pclose(p);
  if (output) *output = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

PostgresServer* PostgresServer::shared(std::string* why) {
  static std::mutex mutex;
  static std::unique_ptr<PostgresServer> server;
  static std::string absent;
  std::lock_guard lock(mutex);
  if (server) return server.get();
  if (!absent.empty()) {
    *why = absent;
    return nullptr;
  }
  // ctest's fixture wrote the URL of the build's server; a program run by itself starts one.
  const std::string url = file_text(fs::path(PAPERNET_TEST_POSTGRES_DIR) / "url");
  if (!url.empty()) {
    auto found =
        std::unique_ptr<PostgresServer>(new PostgresServer(PAPERNET_TEST_POSTGRES_DIR, false));
    found->socket_ = url_parameter(url, "host");
    found->port_ = url_parameter(url, "port");
    while (!found->port_.empty() && found->port_.back() == '\n') found->port_.pop_back();
    try {
      server::pg::Connection probe(found->url());
      server = std::move(found);
      return server.get();
    } catch (const server::StoreError&) {  // a server of an earlier run, gone: start one
    }
  }
  server = start_private(why);
  if (!server) absent = *why;
  return server.get();
}

std::unique_ptr<PostgresServer> PostgresServer::start_private(std::string* why) {
  char dir[] = "/tmp/papernet-pg-XXXXXX";
  if (!mkdtemp(dir)) throw std::runtime_error("mkdtemp failed");
  chmod(dir, 0755);
  auto server = std::unique_ptr<PostgresServer>(new PostgresServer(dir, true));
  std::string output;
  const int code = server->script("start", &output);
  if (code == kNotInstalled) {
    server->owned_ = false;
    fs::remove_all(dir);
    *why = output;
    return nullptr;
  }
  if (code != 0) throw std::runtime_error("scripts/test-postgres.sh start failed:\n" + output);
  const std::string url = output.substr(0, output.find('\n'));
  server->socket_ = url_parameter(url, "host");
  server->port_ = url_parameter(url, "port");
  return server;
}

PostgresServer::~PostgresServer() {
  if (owned_) script("destroy");
}

std::string PostgresServer::url(const std::string& database) const {
  return "postgresql://postgres@/" + database + "?host=" + socket_ + "&port=" + port_;
}

std::string PostgresServer::login_url(const std::string& database,
                                      const std::string& password) const {
  return "postgresql://papernet_login:" + password + "@/" + database + "?host=" + socket_ +
         "&port=" + port_;
}

std::string PostgresServer::create_database() {
  static std::atomic<int> counter{0};
  const std::string name = "pn_" + std::to_string(getpid()) + "_" + std::to_string(counter++) +
                           "_" + server::new_job_id().substr(0, 6);
  query("postgres", "CREATE DATABASE " + name);
  return name;
}

void PostgresServer::drop_database(const std::string& name) {
  query("postgres", "DROP DATABASE IF EXISTS " + name + " WITH (FORCE)");
}

std::string PostgresServer::query(const std::string& database, const std::string& sql) {
  server::pg::Connection c(url(database));
  server::pg::Result r = c.exec(sql);
  return r.rows() > 0 ? r.text(0, 0) : "";
}

void PostgresServer::stop() { EXPECT_EQ(script("stop"), 0); }
void PostgresServer::start() {
  std::string output;
  EXPECT_EQ(script("start", &output), 0) << output;
}
void PostgresServer::restart() { EXPECT_EQ(script("restart"), 0); }

void BothStores::SetUp() {
  server_store_flags().clear();
  if (!postgres()) return;
  std::string why;
  PostgresServer* pg = PostgresServer::shared(&why);
  if (!pg) GTEST_SKIP() << "PostgreSQL is not installed, so this test skips: " << why;
  database_ = pg->create_database();
  // A short lease, so that a job of a killed server runs again within seconds.
  server_store_flags() = {"--store", pg->url(database_), "--lease", "3"};
}

void BothStores::TearDown() {
  server_store_flags().clear();
  std::string why;
  if (!database_.empty()) PostgresServer::shared(&why)->drop_database(database_);
  if (!sqlite_dir_.empty()) fs::remove_all(sqlite_dir_);
}

std::unique_ptr<server::JobStore> BothStores::open_store() {
  if (postgres()) {
    std::string why;
    return std::make_unique<server::PgJobStore>(PostgresServer::shared(&why)->url(database_), 8);
  }
  if (sqlite_dir_.empty()) {
    sqlite_dir_ = (fs::temp_directory_path() / ("papernet_store_" + server::new_job_id())).string();
    fs::create_directories(sqlite_dir_);
  }
  return std::make_unique<server::SqliteJobStore>(sqlite_dir_ + "/jobs.sqlite");
}

std::string store_kind_name(const testing::TestParamInfo<StoreKind>& info) {
  return info.param == StoreKind::Postgres ? "postgres" : "sqlite";
}

}  // namespace papernet::test
