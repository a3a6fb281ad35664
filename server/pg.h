// A small RAII layer over libpq for the PostgreSQL job store (docs/scaling.md): connections
// with statements prepared once each, a pool with reconnection and backoff, and a LISTEN
// connection on a thread of its own.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "server/store_records.h"

typedef struct pg_conn PGconn;
typedef struct pg_result PGresult;

namespace papernet::server::pg {

/// The connection broke while a statement ran (the server restarted, the network failed).
class ConnectionLost : public StoreUnavailable {
 public:
  using StoreUnavailable::StoreUnavailable;
};

/// A statement's parameters, in order: text, numbers, or bytes sent as binary (bytea). Bytes
/// are not copied: they must outlive the statement.
class Params {
 public:
  Params& text(std::string value);
  Params& number(double value);
  Params& number(std::int64_t value);
  Params& bytes(const std::string& value);
  Params& null();

 private:
  friend class Connection;
  struct Value {
    std::string owned;
    const std::string* borrowed = nullptr;
    bool null = false;
  };
  std::vector<Value> values_;
};

/// The rows of one statement. Values of a binary-format result are raw bytes (text and bytea
/// columns only); a text-format result's numbers are parsed by integer() and real().
class Result {
 public:
  explicit Result(PGresult* result) : result_(result) {}
  ~Result();
  Result(Result&& other) noexcept : result_(other.result_) { other.result_ = nullptr; }
  Result(const Result&) = delete;
  Result& operator=(const Result&) = delete;

  int rows() const;
  bool null(int row, int col) const;
  std::string text(int row, int col) const;
  std::int64_t integer(int row, int col) const;
  double real(int row, int col) const;
  bool boolean(int row, int col) const;

 private:
  PGresult* result_;
};

/// One connection. Each statement text is prepared once per connection, then executed.
class Connection {
 public:
  enum class Format { Text, Binary };
  /// \throw StoreUnavailable with libpq's reason (refused, no such host, wrong password...).
  explicit Connection(const std::string& url);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  /// \throw ConnectionLost when the connection broke, StoreError for any other failure.
  Result exec(const std::string& sql, const Params& params = {}, Format format = Format::Text);
  /// Several statements without parameters (a migration).
  void exec_script(const std::string& sql);
  /// BEGIN, `body`, then COMMIT when it returns true and ROLLBACK when it returns false or
  /// throws. Returns what `body` returned.
  bool transaction(const std::function<bool()>& body);
  bool broken() const;
  PGconn* raw() { return conn_; }

 private:
  [[noreturn]] void fail(PGresult* result, const std::string& what);
  PGconn* conn_ = nullptr;
  std::unordered_map<std::string, std::string> prepared_;
};

/// Up to `size` connections, opened when first needed and kept. A connection found broken is
/// dropped with every idle one (a restarted server broke them all) and the operation runs once
/// more on a new connection. Connecting again after a failure waits a backoff that doubles from
/// 100 ms to 2 s; until then operations fail at once with StoreUnavailable instead of hanging.
class Pool {
 public:
  /// Opens the first connection now. \throw StoreUnavailable when it cannot.
  Pool(std::string url, std::size_t size);
  ~Pool();

  /// Runs `body` on a connection of its own. Each store operation is one transaction whose
  /// repetition after a lost connection is harmless, so `body` may run twice.
  void run(const std::function<void(Connection&)>& body);
  std::uint64_t reconnects() const { return reconnects_; }

 private:
  std::unique_ptr<Connection> acquire();
  void give_back(std::unique_ptr<Connection> connection);
  void drop_broken();

  const std::string url_;
  const std::size_t size_;
  std::mutex mutex_;
  std::condition_variable released_;
  std::vector<std::unique_ptr<Connection>> idle_;
  std::size_t open_ = 0;
  std::chrono::steady_clock::time_point next_try_{};
  std::chrono::milliseconds backoff_{0};
  std::string last_error_;
  bool lost_ = false;  // a connection broke since the last successful connect
  std::atomic<std::uint64_t> reconnects_{0};
};

/// LISTEN on `channel` over a connection of its own, on a thread of its own: calls `on_notify`
/// with each payload, and `on_connected` after every (re)connection, since notifications sent
/// while it was away are lost. Reconnects with the same backoff as the pool.
class Listener {
 public:
  Listener(std::string url, std::string channel,
           std::function<void(const std::string& payload)> on_notify,
           std::function<void()> on_connected);
  ~Listener();
  std::uint64_t reconnects() const { return reconnects_; }

 private:
  void loop();
  const std::string url_, channel_;
  std::function<void(const std::string&)> on_notify_;
  std::function<void()> on_connected_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> reconnects_{0};
  std::thread thread_;
};

}  // namespace papernet::server::pg
