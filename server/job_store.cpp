#include "server/job_store.h"

#include <sqlite3.h>

#include <stdexcept>

namespace papernet::server {
namespace {

constexpr const char* kSchema = R"sql(
PRAGMA journal_mode=WAL;
PRAGMA synchronous=NORMAL;
PRAGMA busy_timeout=5000;
CREATE TABLE IF NOT EXISTS jobs(
  seq INTEGER PRIMARY KEY AUTOINCREMENT,
  id TEXT UNIQUE NOT NULL,
  status TEXT NOT NULL,
  created REAL NOT NULL, started REAL NOT NULL DEFAULT 0, finished REAL NOT NULL DEFAULT 0,
  options TEXT NOT NULL, format TEXT NOT NULL, input_bytes INTEGER NOT NULL,
  input_key TEXT NOT NULL, input_faces INTEGER NOT NULL DEFAULT 0,
  faces INTEGER NOT NULL DEFAULT 0, overlaps INTEGER NOT NULL DEFAULT 0,
  result_kind TEXT NOT NULL DEFAULT '', metrics TEXT NOT NULL DEFAULT '{}',
  error TEXT NOT NULL DEFAULT 'null', result_job TEXT NOT NULL DEFAULT '',
  attempts INTEGER NOT NULL DEFAULT 0);
CREATE INDEX IF NOT EXISTS jobs_by_key ON jobs(input_key);
CREATE INDEX IF NOT EXISTS jobs_by_status ON jobs(status);
CREATE TABLE IF NOT EXISTS inputs(job_id TEXT PRIMARY KEY, mesh BLOB NOT NULL);
CREATE TABLE IF NOT EXISTS input_files(job_id TEXT NOT NULL, name TEXT NOT NULL,
  data BLOB NOT NULL, PRIMARY KEY(job_id, name));
CREATE TABLE IF NOT EXISTS results(job_id TEXT NOT NULL, name TEXT NOT NULL,
  content_type TEXT NOT NULL, data BLOB NOT NULL, PRIMARY KEY(job_id, name));
)sql";

constexpr const char* kColumns =
    "seq, id, status, created, started, finished, options, format, input_bytes, input_key, "
    "input_faces, faces, overlaps, result_kind, metrics, error, result_job, attempts";

[[noreturn]] void fail(sqlite3* db, const std::string& what) {
  throw std::runtime_error("job store: " + what + ": " + sqlite3_errmsg(db));
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
  /// True while there is a row.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc != SQLITE_DONE) fail(db_, "step");
    return false;
  }
  void run() { step(); }
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

// BEGIN IMMEDIATE .. COMMIT, rolled back when an exception leaves the scope.
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

JobRecord read_job(const Statement& s) {
  JobRecord j;
  j.seq = s.integer(0);
  j.id = s.text(1);
  j.status = parse_status(s.text(2));
  j.created = s.real(3);
  j.started = s.real(4);
  j.finished = s.real(5);
  j.options = nlohmann::json::parse(s.text(6));
  j.format = s.text(7);
  j.input_bytes = static_cast<std::size_t>(s.integer(8));
  j.input_key = s.text(9);
  j.input_faces = static_cast<std::size_t>(s.integer(10));
  j.faces = static_cast<std::size_t>(s.integer(11));
  j.overlaps = static_cast<std::size_t>(s.integer(12));
  j.result_kind = s.text(13);
  j.metrics = nlohmann::json::parse(s.text(14));
  j.error = nlohmann::json::parse(s.text(15));
  j.result_job = s.text(16);
  j.attempts = static_cast<int>(s.integer(17));
  return j;
}

std::int64_t i64(std::size_t v) { return static_cast<std::int64_t>(v); }

}  // namespace

JobStore::JobStore(const std::string& path) {
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
      SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw std::runtime_error("job store: cannot open '" + path + "': " + message);
  }
  char* error = nullptr;
  if (sqlite3_exec(db_, kSchema, nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string message = error ? error : "unknown error";
    sqlite3_free(error);
    sqlite3_close(db_);
    throw std::runtime_error("job store: cannot prepare '" + path + "': " + message);
  }
}

JobStore::~JobStore() { sqlite3_close(db_); }

void JobStore::insert(JobRecord& job, const JobInput* input) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  Statement(db_,
            "INSERT INTO jobs(id, status, created, started, finished, options, format, "
            "input_bytes, input_key, input_faces, faces, overlaps, result_kind, metrics, error, "
            "result_job, attempts) VALUES(?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)")
      .bind(1, job.id)
      .bind(2, status_name(job.status))
      .bind(3, job.created)
      .bind(4, job.started)
      .bind(5, job.finished)
      .bind(6, job.options.dump())
      .bind(7, job.format)
      .bind(8, i64(job.input_bytes))
      .bind(9, job.input_key)
      .bind(10, i64(job.input_faces))
      .bind(11, i64(job.faces))
      .bind(12, i64(job.overlaps))
      .bind(13, job.result_kind)
      .bind(14, job.metrics.dump())
      .bind(15, job.error.dump())
      .bind(16, job.result_job)
      .bind(17, std::int64_t{job.attempts})
      .run();
  job.seq = sqlite3_last_insert_rowid(db_);
  if (input) {
    Statement(db_, "INSERT INTO inputs(job_id, mesh) VALUES(?,?)")
        .bind(1, job.id)
        .blob(2, input->mesh)
        .run();
    for (const auto& [name, data] : input->external_files)
      Statement(db_, "INSERT INTO input_files(job_id, name, data) VALUES(?,?,?)")
          .bind(1, job.id)
          .bind(2, name)
          .blob(3, data)
          .run();
  }
  tx.commit();
}

std::optional<JobRecord> JobStore::find(const std::string& id) {
  std::lock_guard lock(mutex_);
  Statement s(db_, std::string("SELECT ") + kColumns + " FROM jobs WHERE id=?");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return read_job(s);
}

std::vector<JobRecord> JobStore::list(std::size_t limit, std::int64_t before_seq) {
  std::lock_guard lock(mutex_);
  Statement s(db_, std::string("SELECT ") + kColumns +
                       " FROM jobs WHERE (?=0 OR seq<?) ORDER BY seq DESC LIMIT ?");
  s.bind(1, before_seq).bind(2, before_seq).bind(3, i64(limit));
  std::vector<JobRecord> out;
  while (s.step()) out.push_back(read_job(s));
  return out;
}

std::vector<JobRecord> JobStore::unfinished() {
  std::lock_guard lock(mutex_);
  Statement s(db_, std::string("SELECT ") + kColumns +
                       " FROM jobs WHERE status IN ('queued','running') ORDER BY seq");
  std::vector<JobRecord> out;
  while (s.step()) out.push_back(read_job(s));
  return out;
}

JobInput JobStore::input(const std::string& id) {
  std::lock_guard lock(mutex_);
  JobInput in;
  Statement mesh(db_, "SELECT mesh FROM inputs WHERE job_id=?");
  mesh.bind(1, id);
  if (!mesh.step()) throw std::runtime_error("job store: no stored input for job " + id);
  in.mesh = mesh.text(0);
  Statement files(db_, "SELECT name, data FROM input_files WHERE job_id=?");
  files.bind(1, id);
  while (files.step()) in.external_files[files.text(0)] = files.text(1);
  Statement format(db_, "SELECT format FROM jobs WHERE id=?");
  format.bind(1, id);
  if (format.step()) {
    const std::string name = format.text(0);
    in.format = name == "unknown" ? MeshFormat::Unknown : format_from_extension("x." + name);
  }
  return in;
}

void JobStore::mark_running(const std::string& id, double started) {
  std::lock_guard lock(mutex_);
  Statement(db_, "UPDATE jobs SET status='running', started=?, attempts=attempts+1 WHERE id=?")
      .bind(1, started)
      .bind(2, id)
      .run();
}

void JobStore::requeue(const std::string& id) {
  std::lock_guard lock(mutex_);
  Statement(db_, "UPDATE jobs SET status='queued', started=0 WHERE id=? AND status='running'")
      .bind(1, id)
      .run();
}

void JobStore::finish(const JobRecord& job, const JobOutput* output) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  Statement(db_,
            "UPDATE jobs SET status=?, finished=?, input_faces=?, faces=?, overlaps=?, "
            "result_kind=?, metrics=?, error=?, result_job=? WHERE id=?")
      .bind(1, status_name(job.status))
      .bind(2, job.finished)
      .bind(3, i64(job.input_faces))
      .bind(4, i64(job.faces))
      .bind(5, i64(job.overlaps))
      .bind(6, job.result_kind)
      .bind(7, job.metrics.dump())
      .bind(8, job.error.dump())
      .bind(9, job.result_job)
      .bind(10, job.id)
      .run();
  if (output)
    for (const auto& [name, file] : output->files)
      Statement(db_,
                "INSERT OR REPLACE INTO results(job_id, name, content_type, data) "
                "VALUES(?,?,?,?)")
          .bind(1, job.id)
          .bind(2, name)
          .bind(3, file.content_type)
          .blob(4, file.data)
          .run();
  tx.commit();
}

std::optional<Artifact> JobStore::artifact(const std::string& result_job, const std::string& name) {
  std::lock_guard lock(mutex_);
  Statement s(db_, "SELECT content_type, data FROM results WHERE job_id=? AND name=?");
  s.bind(1, result_job).bind(2, name);
  if (!s.step()) return std::nullopt;
  return Artifact{s.text(0), s.text(1)};
}

std::vector<std::string> JobStore::artifact_names(const std::string& result_job) {
  std::lock_guard lock(mutex_);
  Statement s(db_, "SELECT name FROM results WHERE job_id=? ORDER BY name");
  s.bind(1, result_job);
  std::vector<std::string> out;
  while (s.step()) out.push_back(s.text(0));
  return out;
}

std::optional<JobRecord> JobStore::find_reusable(const std::string& input_key,
                                                 const JobInput& input) {
  std::lock_guard lock(mutex_);
  // The key is a hash; equal bytes make the match certain. External files are in the key.
  Statement s(db_, std::string("SELECT ") + kColumns +
                       " FROM jobs JOIN inputs ON inputs.job_id = jobs.id WHERE input_key=? "
                       "AND status IN ('succeeded','approximated') AND inputs.mesh=? "
                       "ORDER BY seq DESC LIMIT 1");
  s.bind(1, input_key).blob(2, input.mesh);
  if (!s.step()) return std::nullopt;
  return read_job(s);
}

std::map<std::string, std::size_t> JobStore::count_by_status() {
  std::lock_guard lock(mutex_);
  Statement s(db_, "SELECT status, COUNT(*) FROM jobs GROUP BY status");
  std::map<std::string, std::size_t> out;
  while (s.step()) out[s.text(0)] = static_cast<std::size_t>(s.integer(1));
  return out;
}

}  // namespace papernet::server
