#include "server/sqlite_store.h"

#include <sqlite3.h>

#include "core/io/json_text.h"
#include "server/internal/sqlite_statement.h"

namespace papernet::server {
namespace {

using sqlite::fail;
using sqlite::Statement;
using sqlite::Transaction;

constexpr const char* kPragmas = R"sql(
PRAGMA journal_mode=WAL;
PRAGMA synchronous=NORMAL;
PRAGMA busy_timeout=5000;
)sql";

// The schema's versions, applied in order; PRAGMA user_version says how many a file has.
// Version 1 is the schema from before versioning, so files it made migrate from there.
constexpr const char* kMigrations[] = {
    R"sql(
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
)sql",
    // Claims and leases (docs/scaling.md), published progress and intermediates.
    R"sql(
ALTER TABLE jobs ADD COLUMN claimed_by TEXT NOT NULL DEFAULT '';
ALTER TABLE jobs ADD COLUMN lease_until REAL NOT NULL DEFAULT 0;
ALTER TABLE jobs ADD COLUMN cancel_requested INTEGER NOT NULL DEFAULT 0;
ALTER TABLE jobs ADD COLUMN progress TEXT NOT NULL DEFAULT 'null';
ALTER TABLE jobs ADD COLUMN intermediate TEXT NOT NULL DEFAULT 'null';
CREATE TABLE IF NOT EXISTS intermediates(job_id TEXT NOT NULL, name TEXT NOT NULL,
  content_type TEXT NOT NULL, data BLOB NOT NULL, PRIMARY KEY(job_id, name));
)sql",
    // Tenants (API keys): a job belongs to the tenant that submitted it.
    R"sql(
ALTER TABLE jobs ADD COLUMN tenant TEXT NOT NULL DEFAULT '';
CREATE INDEX IF NOT EXISTS jobs_by_tenant ON jobs(tenant, seq);
)sql",
    // Idempotency-Key: per tenant, what a key stood for (24 h).
    R"sql(
CREATE TABLE IF NOT EXISTS idempotency(tenant TEXT NOT NULL, key TEXT NOT NULL,
  request_hash TEXT NOT NULL, job_id TEXT NOT NULL, created REAL NOT NULL,
  PRIMARY KEY(tenant, key));
)sql",
    // Retention: an expired job keeps its row (410), not its input or files.
    R"sql(
ALTER TABLE jobs ADD COLUMN expired INTEGER NOT NULL DEFAULT 0;
)sql",
    // Webhooks: a job's callback delivery, kept until it is done so that a restart resumes it.
    R"sql(
CREATE TABLE IF NOT EXISTS webhooks(job_id TEXT PRIMARY KEY, url TEXT NOT NULL,
  state TEXT NOT NULL DEFAULT 'pending', attempts TEXT NOT NULL DEFAULT '[]',
  next_at REAL NOT NULL DEFAULT 0, claimed_by TEXT NOT NULL DEFAULT '',
  lease_until REAL NOT NULL DEFAULT 0);
CREATE INDEX IF NOT EXISTS webhooks_pending ON webhooks(next_at) WHERE state='pending';
)sql",
};

// The store's clock, in seconds since the epoch, for leases.
constexpr const char* kNow = "((julianday('now') - 2440587.5) * 86400.0)";

constexpr const char* kColumns =
    "seq, id, status, created, started, finished, options, format, input_bytes, input_key, "
    "input_faces, faces, overlaps, result_kind, metrics, error, result_job, attempts, "
    "claimed_by, cancel_requested, progress, intermediate, "
    "(SELECT group_concat(r.name, '/') FROM results r WHERE r.job_id = result_job), tenant, "
    "expired";

// A running job held by this claim.
constexpr const char* kHeld = "id=? AND claimed_by=? AND attempts=? AND status='running'";

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
  j.node = s.text(18);
  j.cancel_requested = s.integer(19) != 0;
  j.progress = nlohmann::json::parse(s.text(20));
  j.intermediate = nlohmann::json::parse(s.text(21));
  j.result_files = split_file_names(s.text(22));
  j.tenant = s.text(23);
  j.expired = s.integer(24) != 0;
  return j;
}

std::int64_t i64(std::size_t v) { return static_cast<std::int64_t>(v); }

void exec_script(sqlite3* db, const char* sql, const std::string& path) {
  char* error = nullptr;
  if (sqlite3_exec(db, sql, nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string message = error ? error : "unknown error";
    sqlite3_free(error);
    throw StoreError("job store: cannot prepare '" + path + "': " + message);
  }
}

void migrate(sqlite3* db, const std::string& path) {
  exec_script(db, kPragmas, path);
  int version = 0;
  {
    Statement s(db, "PRAGMA user_version");
    if (s.step()) version = static_cast<int>(s.integer(0));
  }
  const int known = static_cast<int>(std::size(kMigrations));
  if (version > known)
    throw StoreError("job store: '" + path + "' has schema version " + std::to_string(version) +
                     ", newer than this papernet knows (" + std::to_string(known) + ")");
  for (int v = version + 1; v <= known; ++v) {
    Transaction tx(db);
    exec_script(db, kMigrations[v - 1], path);
    exec_script(db, ("PRAGMA user_version=" + std::to_string(v)).c_str(), path);
    tx.commit();
  }
}

}  // namespace

SqliteJobStore::SqliteJobStore(const std::string& path) {
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
      SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw StoreError("job store: cannot open '" + path + "': " + message);
  }
  try {
    migrate(db_, path);
  } catch (...) {
    sqlite3_close(db_);
    throw;
  }
}

SqliteJobStore::~SqliteJobStore() { sqlite3_close(db_); }

bool SqliteJobStore::insert(JobRecord& job, const JobInput* input, std::size_t queue_limit) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  if (job.status == JobStatus::Queued) {
    Statement queued(db_, "SELECT COUNT(*) FROM jobs WHERE status='queued'");
    if (queued.step() && queued.integer(0) >= i64(queue_limit)) return false;
  }
  Statement(db_,
            "INSERT INTO jobs(id, status, created, started, finished, options, format, "
            "input_bytes, input_key, input_faces, faces, overlaps, result_kind, metrics, error, "
            "result_job, attempts, tenant) VALUES(?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)")
      .bind(1, job.id)
      .bind(2, status_name(job.status))
      .bind(3, job.created)
      .bind(4, job.started)
      .bind(5, job.finished)
      .bind(6, json_text(job.options))
      .bind(7, job.format)
      .bind(8, i64(job.input_bytes))
      .bind(9, job.input_key)
      .bind(10, i64(job.input_faces))
      .bind(11, i64(job.faces))
      .bind(12, i64(job.overlaps))
      .bind(13, job.result_kind)
      .bind(14, json_text(job.metrics))
      .bind(15, json_text(job.error))
      .bind(16, job.result_job)
      .bind(17, std::int64_t{job.attempts})
      .bind(18, job.tenant)
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
  if (const auto url = job.options.find("callback_url");
      url != job.options.end() && url->is_string())
    Statement(db_, "INSERT INTO webhooks(job_id, url) VALUES(?,?)")
        .bind(1, job.id)
        .bind(2, url->get<std::string>())
        .run();
  tx.commit();
  return true;
}

std::optional<JobRecord> SqliteJobStore::find(const std::string& id) {
  std::lock_guard lock(mutex_);
  Statement s(db_, std::string("SELECT ") + kColumns + " FROM jobs WHERE id=?");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return read_job(s);
}

std::vector<JobRecord> SqliteJobStore::list(const std::string& tenant, std::size_t limit,
                                            std::int64_t before_seq) {
  std::lock_guard lock(mutex_);
  Statement s(db_, std::string("SELECT ") + kColumns +
                       " FROM jobs WHERE tenant=? AND expired=0 AND (?=0 OR seq<?) "
                       "ORDER BY seq DESC LIMIT ?");
  s.bind(1, tenant).bind(2, before_seq).bind(3, before_seq).bind(4, i64(limit));
  std::vector<JobRecord> out;
  while (s.step()) out.push_back(read_job(s));
  return out;
}

JobInput SqliteJobStore::input(const std::string& id) {
  std::lock_guard lock(mutex_);
  JobInput in;
  Statement mesh(db_,
                 "SELECT inputs.mesh, jobs.format FROM inputs JOIN jobs ON jobs.id=job_id "
                 "WHERE job_id=?");
  mesh.bind(1, id);
  if (!mesh.step()) throw StoreError("job store: no stored input for job " + id);
  in.mesh = mesh.text(0);
  in.format = format_of_record(mesh.text(1));
  Statement files(db_, "SELECT name, data FROM input_files WHERE job_id=?");
  files.bind(1, id);
  while (files.step()) in.external_files[files.text(0)] = files.text(1);
  return in;
}

std::optional<JobRecord> SqliteJobStore::find_reusable(const std::string& tenant,
                                                       const std::string& input_key,
                                                       const JobInput& input) {
  std::lock_guard lock(mutex_);
  // The key is a hash; equal bytes make the match certain. External files are in the key.
  Statement s(db_, std::string("SELECT ") + kColumns +
                       " FROM jobs JOIN inputs ON inputs.job_id = jobs.id WHERE input_key=? "
                       "AND status IN ('succeeded','approximated') AND inputs.mesh=? "
                       "AND tenant=? ORDER BY seq DESC LIMIT 1");
  s.bind(1, input_key).blob(2, input.mesh).bind(3, tenant);
  if (!s.step()) return std::nullopt;
  return read_job(s);
}

IdempotencyRecord SqliteJobStore::remember_idempotency(const std::string& tenant,
                                                       const std::string& key,
                                                       const IdempotencyRecord& record,
                                                       double since) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  Statement earlier(db_,
                    "SELECT request_hash, job_id, created FROM idempotency WHERE tenant=? AND "
                    "key=? AND created>=?");
  earlier.bind(1, tenant).bind(2, key).bind(3, since);
  if (earlier.step()) return {earlier.text(0), earlier.text(1), earlier.real(2)};
  Statement(db_,
            "INSERT OR REPLACE INTO idempotency(tenant, key, request_hash, job_id, created) "
            "VALUES(?,?,?,?,?)")
      .bind(1, tenant)
      .bind(2, key)
      .bind(3, record.request_hash)
      .bind(4, record.job_id)
      .bind(5, record.created)
      .run();
  tx.commit();
  return record;
}

void SqliteJobStore::forget_idempotency(const std::string& tenant, const std::string& key,
                                        const std::string& job_id) {
  std::lock_guard lock(mutex_);
  Statement(db_, "DELETE FROM idempotency WHERE tenant=? AND key=? AND job_id=?")
      .bind(1, tenant)
      .bind(2, key)
      .bind(3, job_id)
      .run();
}

std::size_t SqliteJobStore::expire(double finished_before, double keys_before) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  const int expired =
      Statement(db_,
                "UPDATE jobs SET expired=1 WHERE expired=0 AND finished>0 AND finished<? AND "
                "status IN ('succeeded','approximated','failed','cancelled')")
          .bind(1, finished_before)
          .run();
  if (expired > 0) {
    for (const char* table : {"inputs", "input_files", "intermediates"})
      Statement(db_, std::string("DELETE FROM ") + table +
                         " WHERE job_id IN (SELECT id FROM jobs WHERE expired=1)")
          .run();
  }
  // Also after earlier sweeps: a result kept for a job that reused it goes once that expired.
  Statement(db_,
            "DELETE FROM results WHERE job_id IN (SELECT id FROM jobs WHERE expired=1) AND "
            "job_id NOT IN (SELECT result_job FROM jobs WHERE expired=0)")
      .run();
  Statement(db_, "DELETE FROM idempotency WHERE created<?").bind(1, keys_before).run();
  if (expired > 0)
    Statement(db_, "DELETE FROM webhooks WHERE job_id IN (SELECT id FROM jobs WHERE expired=1)")
        .run();
  tx.commit();
  return static_cast<std::size_t>(expired);
}

std::uint64_t SqliteJobStore::stored_bytes() {
  std::lock_guard lock(mutex_);
  // length() of a BLOB reads its size from the record, not its bytes.
  Statement s(db_,
              "SELECT (SELECT COALESCE(SUM(length(mesh)), 0) FROM inputs) + "
              "(SELECT COALESCE(SUM(length(data)), 0) FROM input_files) + "
              "(SELECT COALESCE(SUM(length(data)), 0) FROM intermediates) + "
              "(SELECT COALESCE(SUM(length(data)), 0) FROM results)");
  return s.step() ? static_cast<std::uint64_t>(s.integer(0)) : 0;
}

std::optional<double> SqliteJobStore::oldest_finished() {
  std::lock_guard lock(mutex_);
  Statement s(db_,
              "SELECT COALESCE(MIN(finished), 0) FROM jobs WHERE expired=0 AND finished>0 AND "
              "status IN ('succeeded','approximated','failed','cancelled')");
  if (!s.step() || !(s.real(0) > 0)) return std::nullopt;
  return s.real(0);
}

std::size_t SqliteJobStore::queued_count(const std::string& tenant) {
  std::lock_guard lock(mutex_);
  Statement s(db_, "SELECT COUNT(*) FROM jobs WHERE status='queued' AND tenant=?");
  s.bind(1, tenant);
  return s.step() ? static_cast<std::size_t>(s.integer(0)) : 0;
}

std::map<std::string, std::size_t> SqliteJobStore::queued_by_tenant() {
  std::lock_guard lock(mutex_);
  Statement s(db_, "SELECT tenant, COUNT(*) FROM jobs WHERE status='queued' GROUP BY tenant");
  std::map<std::string, std::size_t> out;
  while (s.step()) out[s.text(0)] = static_cast<std::size_t>(s.integer(1));
  return out;
}

std::map<std::string, std::size_t> SqliteJobStore::count_by_status() {
  std::lock_guard lock(mutex_);
  Statement s(db_, "SELECT status, COUNT(*) FROM jobs WHERE expired=0 GROUP BY status");
  std::map<std::string, std::size_t> out;
  while (s.step()) out[s.text(0)] = static_cast<std::size_t>(s.integer(1));
  return out;
}

std::size_t SqliteJobStore::queue_position(std::int64_t seq) {
  std::lock_guard lock(mutex_);
  Statement s(db_, "SELECT COUNT(*) FROM jobs WHERE status='queued' AND seq<=?");
  s.bind(1, seq);
  return s.step() ? static_cast<std::size_t>(s.integer(0)) : 0;
}

std::vector<std::string> SqliteJobStore::recover_interrupted() {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  std::vector<std::string> ids;
  Statement running(db_, "SELECT id FROM jobs WHERE status='running' ORDER BY seq");
  while (running.step()) ids.push_back(running.text(0));
  Statement(db_,
            "UPDATE jobs SET status='queued', started=0, claimed_by='', lease_until=0, "
            "progress='null', intermediate='null' WHERE status='running'")
      .run();
  Statement(db_, "DELETE FROM intermediates").run();
  tx.commit();
  return ids;
}

std::optional<ClaimedJob> SqliteJobStore::claim(const std::string& node, double lease_seconds,
                                                double started) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  Statement next(db_, std::string("SELECT seq, id, status, claimed_by FROM jobs WHERE "
                                  "status='queued' OR (status='running' AND lease_until<=") +
                          kNow + ") ORDER BY seq LIMIT 1");
  if (!next.step()) return std::nullopt;
  const std::int64_t seq = next.integer(0);
  const std::string id = next.text(1);
  ClaimedJob claimed;
  if (next.text(2) == "running") claimed.expired_node = next.text(3);
  Statement(db_, std::string("UPDATE jobs SET status='running', claimed_by=?, lease_until=") +
                     kNow +
                     "+?, attempts=attempts+1, started=?, progress='null', intermediate='null' "
                     "WHERE seq=?")
      .bind(1, node)
      .bind(2, lease_seconds)
      .bind(3, started)
      .bind(4, seq)
      .run();
  Statement(db_, "DELETE FROM intermediates WHERE job_id=?").bind(1, id).run();
  Statement row(db_, std::string("SELECT ") + kColumns + " FROM jobs WHERE seq=?");
  row.bind(1, seq);
  row.step();
  claimed.record = read_job(row);
  tx.commit();
  return claimed;
}

LeaseState SqliteJobStore::renew(const std::string& id, const Claim& claim, double lease_seconds,
                                 const nlohmann::json* progress) {
  std::lock_guard lock(mutex_);
  Statement s(db_, std::string("UPDATE jobs SET lease_until=") + kNow +
                       "+?, progress=coalesce(?, progress) WHERE " + kHeld +
                       " RETURNING cancel_requested");
  s.bind(1, lease_seconds);
  if (progress) s.bind(2, progress->dump());
  s.held(3, id, claim);
  LeaseState state;
  if (s.step()) {
    state.held = true;
    state.cancel_requested = s.integer(0) != 0;
  }
  return state;
}

bool SqliteJobStore::put_intermediate(const std::string& id, const Claim& claim,
                                      const JobOutput& output) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  if (Statement(db_, std::string("UPDATE jobs SET intermediate=? WHERE ") + kHeld)
          .bind(1, json_text(intermediate_level_json(output)))
          .held(2, id, claim)
          .run() == 0)
    return false;
  Statement(db_, "DELETE FROM intermediates WHERE job_id=?").bind(1, id).run();
  for (const auto& [name, file] : output.files)
    Statement(db_, "INSERT INTO intermediates(job_id, name, content_type, data) VALUES(?,?,?,?)")
        .bind(1, id)
        .bind(2, name)
        .bind(3, file.content_type)
        .blob(4, file.data)
        .run();
  tx.commit();
  return true;
}

std::optional<IntermediateFile> SqliteJobStore::intermediate(const std::string& id,
                                                             const std::string& name) {
  std::lock_guard lock(mutex_);
  Statement s(db_,
              "SELECT i.content_type, i.data, j.intermediate FROM intermediates i JOIN jobs j ON "
              "j.id=i.job_id WHERE i.job_id=? AND i.name=? AND j.status='running'");
  s.bind(1, id).bind(2, name);
  if (!s.step()) return std::nullopt;
  const auto level = intermediate_level_from_json(nlohmann::json::parse(s.text(2)));
  if (!level) return std::nullopt;
  return IntermediateFile{{s.text(0), s.text(1)}, level->faces, level->input_faces};
}

bool SqliteJobStore::finish(const JobRecord& job, const Claim& claim, const JobOutput* output) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  if (Statement(db_, std::string("UPDATE jobs SET status=?, finished=?, input_faces=?, faces=?, "
                                 "overlaps=?, result_kind=?, metrics=?, error=?, result_job=?, "
                                 "lease_until=0, progress='null', intermediate='null' WHERE ") +
                         kHeld)
          .bind(1, status_name(job.status))
          .bind(2, job.finished)
          .bind(3, i64(job.input_faces))
          .bind(4, i64(job.faces))
          .bind(5, i64(job.overlaps))
          .bind(6, job.result_kind)
          .bind(7, json_text(job.metrics))
          .bind(8, json_text(job.error))
          .bind(9, job.result_job)
          .held(10, job.id, claim)
          .run() == 0)
    return false;
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
  Statement(db_, "DELETE FROM intermediates WHERE job_id=?").bind(1, job.id).run();
  tx.commit();
  return true;
}

bool SqliteJobStore::release(const std::string& id, const Claim& claim) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  if (Statement(db_, std::string("UPDATE jobs SET status='queued', started=0, claimed_by='', "
                                 "lease_until=0, progress='null', intermediate='null' WHERE ") +
                         kHeld)
          .held(1, id, claim)
          .run() == 0)
    return false;
  Statement(db_, "DELETE FROM intermediates WHERE job_id=?").bind(1, id).run();
  tx.commit();
  return true;
}

CancelOutcome SqliteJobStore::cancel(const std::string& id, const nlohmann::json& error,
                                     double finished) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  CancelOutcome outcome = CancelOutcome::NotActive;
  if (Statement(db_,
                "UPDATE jobs SET status='cancelled', finished=?, error=? "
                "WHERE id=? AND status='queued'")
          .bind(1, finished)
          .bind(2, json_text(error))
          .bind(3, id)
          .run() > 0)
    outcome = CancelOutcome::Cancelled;
  else if (Statement(db_, "UPDATE jobs SET cancel_requested=1 WHERE id=? AND status='running'")
               .bind(1, id)
               .run() > 0)
    outcome = CancelOutcome::Requested;
  tx.commit();
  return outcome;
}

std::optional<Artifact> SqliteJobStore::artifact(const std::string& result_job,
                                                 const std::string& name) {
  std::lock_guard lock(mutex_);
  Statement s(db_, "SELECT content_type, data FROM results WHERE job_id=? AND name=?");
  s.bind(1, result_job).bind(2, name);
  if (!s.step()) return std::nullopt;
  return Artifact{s.text(0), s.text(1)};
}

}  // namespace papernet::server
