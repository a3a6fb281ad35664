// The SQLite store's statement and transaction helpers, shared by its source files
// (sqlite_store.cpp, sqlite_webhooks.cpp).
#pragma once

#include <sqlite3.h>

#include <cstdint>
#include <string>

#include "server/store_records.h"

namespace papernet::server::sqlite {

[[noreturn]] inline void fail(sqlite3* db, const std::string& what) {
  throw StoreError("job store: " + what + ": " + sqlite3_errmsg(db));
}

// One prepared statement; binds by position (1-based), finalised on scope exit.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK) fail(db, "prepare");
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int i, const std::string& text) {
    sqlite3_bind_text(stmt_, i, text.data(), static_cast<int>(text.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Statement& blob(int i, const std::string& data) {
    sqlite3_bind_blob64(stmt_, i, data.data(), data.size(), SQLITE_STATIC);
    return *this;
  }
  Statement& bind(int i, double v) {
    sqlite3_bind_double(stmt_, i, v);
    return *this;
  }
  Statement& bind(int i, std::int64_t v) {
    sqlite3_bind_int64(stmt_, i, v);
    return *this;
  }
  // The three parameters of kHeld, from `first` on.
  Statement& held(int first, const std::string& id, const Claim& claim) {
    return bind(first, id).bind(first + 1, claim.node).bind(first + 2, std::int64_t{claim.attempt});
  }
  /// True while there is a row.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc != SQLITE_DONE) fail(db_, "step");
    return false;
  }
  /// Runs a statement without rows; returns the rows it changed.
  int run() {
    step();
    return sqlite3_changes(db_);
  }
  std::string text(int col) const {
    const auto* p = static_cast<const char*>(sqlite3_column_blob(stmt_, col));
    return p ? std::string(p, static_cast<std::size_t>(sqlite3_column_bytes(stmt_, col)))
             : std::string();
  }
  double real(int col) const { return sqlite3_column_double(stmt_, col); }
  std::int64_t integer(int col) const { return sqlite3_column_int64(stmt_, col); }

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

// BEGIN IMMEDIATE .. COMMIT, rolled back when an exception or an early return leaves the scope.
class Transaction {
 public:
  explicit Transaction(sqlite3* db) : db_(db) { exec("BEGIN IMMEDIATE"); }
  ~Transaction() {
    if (!done_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  void commit() {
    exec("COMMIT");
    done_ = true;
  }

 private:
  void exec(const char* sql) {
    if (sqlite3_exec(db_, sql, nullptr, nullptr, nullptr) != SQLITE_OK) fail(db_, sql);
  }
  sqlite3* db_;
  bool done_ = false;
};

}  // namespace papernet::server::sqlite
