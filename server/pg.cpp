#include "server/pg.h"

#include <libpq-fe.h>
#include <poll.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>

#include "server/job_store.h"
#include "server/metrics.h"

namespace papernet::server::pg {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

constexpr std::chrono::milliseconds kMinBackoff = 100ms, kMaxBackoff = 2000ms;

std::chrono::milliseconds next_backoff(std::chrono::milliseconds backoff) {
  return std::clamp(backoff * 2, kMinBackoff, kMaxBackoff);
}

// libpq's messages end with a newline and may span lines; one line reads better in a log.
std::string one_line(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  while (!message.empty() && message.back() == ' ') message.pop_back();
  return message;
}

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace

Params& Params::text(std::string value) {
  values_.push_back({std::move(value), nullptr, false});
  return *this;
}
Params& Params::number(double value) { return text(number_text(value)); }
Params& Params::number(std::int64_t value) { return text(std::to_string(value)); }
Params& Params::bytes(const std::string& value) {
  values_.push_back({{}, &value, false});
  return *this;
}
Params& Params::null() {
  values_.push_back({{}, nullptr, true});
  return *this;
}

Result::~Result() { PQclear(result_); }
int Result::rows() const { return PQntuples(result_); }
bool Result::null(int row, int col) const { return PQgetisnull(result_, row, col) != 0; }
std::string Result::text(int row, int col) const {
  return std::string(PQgetvalue(result_, row, col),
                     static_cast<std::size_t>(PQgetlength(result_, row, col)));
}
std::int64_t Result::integer(int row, int col) const {
  const char* v = PQgetvalue(result_, row, col);
  std::int64_t out = 0;
  std::from_chars(v, v + PQgetlength(result_, row, col), out);
  return out;
}
double Result::real(int row, int col) const {
  return std::strtod(PQgetvalue(result_, row, col), nullptr);
}
bool Result::boolean(int row, int col) const { return PQgetvalue(result_, row, col)[0] == 't'; }

Connection::Connection(const std::string& url) {
  // Defaults first: what the URL says wins (expand_dbname). TCP keepalives find a server that
  // vanished without closing the connection within half a minute.
  const char* keys[] = {"connect_timeout",
                        "application_name",
                        "keepalives_idle",
                        "keepalives_interval",
                        "keepalives_count",
                        "dbname",
                        nullptr};
  const char* values[] = {"5", "papernet", "10", "5", "3", url.c_str(), nullptr};
  conn_ = PQconnectdbParams(keys, values, 1);
  if (!conn_) throw StoreUnavailable("job store: out of memory connecting to the database");
  if (PQstatus(conn_) != CONNECTION_OK) {
    const std::string message = one_line(PQerrorMessage(conn_));
    PQfinish(conn_);
    conn_ = nullptr;
    throw StoreUnavailable("job store: cannot connect to " + redact_store_url(url) + ": " +
                           message);
  }
  // Notices (such as "relation already exists, skipping") are not for the service's log.
  PQsetNoticeProcessor(
      conn_, [](void*, const char*) {}, nullptr);
}

Connection::~Connection() { PQfinish(conn_); }

bool Connection::broken() const { return PQstatus(conn_) != CONNECTION_OK; }

void Connection::fail(PGresult* result, const std::string& what) {
  const std::string message =
      one_line(result && *PQresultErrorMessage(result) ? PQresultErrorMessage(result)
                                                       : PQerrorMessage(conn_));
  const char* field = result ? PQresultErrorField(result, PG_DIAG_SQLSTATE) : nullptr;
  const std::string state = field ? field : "";
  PQclear(result);
  // Class 08 is a connection exception; 57P01-57P03 a server that shuts down or restarts.
  if (broken() || state.rfind("08", 0) == 0 || state.rfind("57P0", 0) == 0)
    throw ConnectionLost("job store: lost the database connection (" + what + "): " + message);
  throw StoreError("job store: " + message);
}

Result Connection::exec(const std::string& sql, const Params& params, Format format) {
  const int n = static_cast<int>(params.values_.size());
  auto it = prepared_.find(sql);
  if (it == prepared_.end()) {
    const std::string name = "papernet_" + std::to_string(prepared_.size() + 1);
    PGresult* r = PQprepare(conn_, name.c_str(), sql.c_str(), n, nullptr);
    if (PQresultStatus(r) != PGRES_COMMAND_OK) fail(r, "prepare");
    PQclear(r);
    it = prepared_.emplace(sql, name).first;
  }
  std::vector<const char*> values(params.values_.size());
  std::vector<int> lengths(values.size()), formats(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const Params::Value& v = params.values_[i];
    const std::string* s = v.borrowed ? v.borrowed : &v.owned;
    values[i] = v.null ? nullptr : s->data();
    lengths[i] = static_cast<int>(s->size());
    formats[i] = v.borrowed ? 1 : 0;
  }
  PGresult* r = PQexecPrepared(conn_, it->second.c_str(), n, values.data(), lengths.data(),
                               formats.data(), format == Format::Binary ? 1 : 0);
  const ExecStatusType status = PQresultStatus(r);
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) fail(r, "statement");
  return Result(r);
}

void Connection::exec_script(const std::string& sql) {
  PGresult* r = PQexec(conn_, sql.c_str());
  const ExecStatusType status = PQresultStatus(r);
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) fail(r, "script");
  PQclear(r);
}

bool Connection::transaction(const std::function<bool()>& body) {
  exec_script("BEGIN");
  bool commit = false;
  try {
    commit = body();
  } catch (...) {
    if (!broken()) {
      try {
        exec_script("ROLLBACK");
      } catch (const StoreError&) {  // the first error is the one to report
      }
    }
    throw;
  }
  exec_script(commit ? "COMMIT" : "ROLLBACK");
  return commit;
}

Pool::Pool(std::string url, std::size_t size)
    : url_(std::move(url)), size_(std::max<std::size_t>(1, size)) {
  idle_.push_back(std::make_unique<Connection>(url_));
  open_ = 1;
}

Pool::~Pool() = default;

std::unique_ptr<Connection> Pool::acquire() {
  std::unique_lock lock(mutex_);
  // The pool has a connection for every thread that uses it; waiting is the exception.
  if (!released_.wait_for(lock, 10s, [&] { return !idle_.empty() || open_ < size_; }))
    throw StoreUnavailable("job store: all " + std::to_string(size_) +
                           " database connections stayed busy for 10 s");
  if (!idle_.empty()) {
    std::unique_ptr<Connection> c = std::move(idle_.back());
    idle_.pop_back();
    return c;
  }
  if (Clock::now() < next_try_)
    throw StoreUnavailable("job store: the database is unavailable (" + last_error_ +
                           "); trying again shortly");
  ++open_;
  lock.unlock();
  try {
    auto c = std::make_unique<Connection>(url_);
    lock.lock();
    backoff_ = 0ms;
    if (lost_) {
      lost_ = false;
      ++reconnects_;
      log_line("job store: connected to the database again");
    }
    return c;
  } catch (const StoreError& e) {
    lock.lock();
    --open_;
    backoff_ = next_backoff(backoff_);
    next_try_ = Clock::now() + backoff_;
    last_error_ = e.what();
    released_.notify_one();
    throw;
  }
}

void Pool::give_back(std::unique_ptr<Connection> connection) {
  std::lock_guard lock(mutex_);
  idle_.push_back(std::move(connection));
  released_.notify_one();
}

void Pool::drop_broken() {
  std::lock_guard lock(mutex_);
  // The broken connection itself is already gone; the idle ones most likely broke with it.
  open_ -= 1 + idle_.size();
  idle_.clear();
  if (!lost_) log_line("job store: lost the database connection; reconnecting");
  lost_ = true;
  released_.notify_all();
}

void Pool::run(const std::function<void(Connection&)>& body) {
  for (int attempt = 0;; ++attempt) {
    std::unique_ptr<Connection> c = acquire();
    try {
      body(*c);
    } catch (const ConnectionLost&) {
      c.reset();
      drop_broken();
      if (attempt > 0) throw;
      continue;
    } catch (...) {
      if (c->broken()) {
        c.reset();
        drop_broken();
      } else {
        give_back(std::move(c));
      }
      throw;
    }
    give_back(std::move(c));
    return;
  }
}

Listener::Listener(std::string url, std::string channel,
                   std::function<void(const std::string&)> on_notify,
                   std::function<void()> on_connected)
    : url_(std::move(url)),
      channel_(std::move(channel)),
      on_notify_(std::move(on_notify)),
      on_connected_(std::move(on_connected)),
      thread_([this] { loop(); }) {}

Listener::~Listener() {
  stop_ = true;
  thread_.join();
}

void Listener::loop() {
  std::chrono::milliseconds backoff{0};
  bool lost = false;
  while (!stop_) {
    std::unique_ptr<Connection> c;
    try {
      c = std::make_unique<Connection>(url_);
      c->exec_script("LISTEN " + channel_);
    } catch (const StoreError&) {
      backoff = next_backoff(backoff);
      for (auto end = Clock::now() + backoff; !stop_ && Clock::now() < end;)
        std::this_thread::sleep_for(50ms);
      continue;
    }
    backoff = 0ms;
    if (lost) {
      ++reconnects_;
      log_line("job store: listening for other nodes' changes again");
    }
    on_connected_();
    PGconn* raw = c->raw();
    while (!stop_) {
      pollfd p{PQsocket(raw), POLLIN, 0};
      const int n = ::poll(&p, 1, 250);
      if (n < 0 && errno != EINTR) break;
      if (n <= 0) continue;
      if (!PQconsumeInput(raw) || PQstatus(raw) != CONNECTION_OK) break;
      while (PGnotify* note = PQnotifies(raw)) {
        const std::string payload = note->extra;
        PQfreemem(note);
        on_notify_(payload);
      }
    }
    if (!stop_) {
      lost = true;
      log_line(
          "job store: lost the LISTEN connection; other nodes' changes are polled until "
          "it is back");
    }
  }
}

}  // namespace papernet::server::pg
