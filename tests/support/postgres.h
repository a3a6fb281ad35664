// A real PostgreSQL server for the tests (scripts/test-postgres.sh starts it from Debian's
// postgresql package as an unprivileged user), and the suites that run against both stores.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "server/job_store.h"

namespace papernet::test {

/// One server in a directory of its own, reached through its Unix socket.
class PostgresServer {
 public:
  /// The server ctest's "postgres" fixture started for this build, or (when a test program
  /// runs by itself) one this process starts and removes at exit. nullptr when PostgreSQL is
  /// not installed; `why` then says so.
  static PostgresServer* shared(std::string* why);
  /// A server of the caller's own, which it may stop and restart. nullptr as above.
  static std::unique_ptr<PostgresServer> start_private(std::string* why);
  ~PostgresServer();
  PostgresServer(const PostgresServer&) = delete;
  PostgresServer& operator=(const PostgresServer&) = delete;

  /// The URL of `database` as the superuser ("postgres", no password).
  std::string url(const std::string& database = "postgres") const;
  /// The URL of `database` with `password` for the login papernet_login (whose password is
  /// "papernet").
  std::string login_url(const std::string& database, const std::string& password) const;
  /// Creates an empty database with a new name; returns its name.
  std::string create_database();
  void drop_database(const std::string& name);
  /// Runs one SQL statement as the superuser; returns the first column of the first row.
  std::string query(const std::string& database, const std::string& sql);

  void stop();
  void start();
  void restart();

 private:
  PostgresServer(std::string dir, bool owned) : dir_(std::move(dir)), owned_(owned) {}
  int script(const std::string& command, std::string* output = nullptr) const;
  std::string dir_;
  std::string socket_, port_;
  bool owned_;
};

/// Flags every `Server` (serve_process.h) a test starts gets before its own: the store of the
/// running BothStores test.
std::vector<std::string>& server_store_flags();

enum class StoreKind { Sqlite, Postgres };

/// Base of the suites that run against both stores (INSTANTIATE_BOTH_STORES). For PostgreSQL
/// each test gets a database of its own on the shared server, and the test's `Server`
/// processes (serve_process.h) use it; without PostgreSQL installed those tests skip, saying so.
class BothStores : public testing::TestWithParam<StoreKind> {
 protected:
  void SetUp() override;
  void TearDown() override;
  bool postgres() const { return GetParam() == StoreKind::Postgres; }
  /// The store for tests of the job service in this process: a new SQLite file, or the test's
  /// database. Opened again, it is the same store.
  std::unique_ptr<server::JobStore> open_store();

 private:
  std::string database_, sqlite_dir_;
};

std::string store_kind_name(const testing::TestParamInfo<StoreKind>& info);

/// GTEST_SKIPs the test (with why) when PostgreSQL is not installed; else the shared server.
#define PAPERNET_SHARED_POSTGRES(server)                                                          \
  std::string server##_why;                                                                       \
  papernet::test::PostgresServer* server = papernet::test::PostgresServer::shared(&server##_why); \
  if (!server) GTEST_SKIP() << server##_why

}  // namespace papernet::test

#define INSTANTIATE_BOTH_STORES(Suite)                                                         \
  INSTANTIATE_TEST_SUITE_P(                                                                    \
      Stores, Suite,                                                                           \
      testing::Values(papernet::test::StoreKind::Sqlite, papernet::test::StoreKind::Postgres), \
      papernet::test::store_kind_name)
