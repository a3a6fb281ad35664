#include "server/pg_store.h"

#include "core/io/json_text.h"

namespace papernet::server {
namespace {

using pg::Connection;
using pg::Params;
using pg::Result;

// Advisory lock key: one queue-length check at a time (pg_schema.cpp's schema lock is another).
constexpr std::int64_t kQueueLock = 0x7061706572'02;

constexpr const char* kColumns =
    "seq, id, status, created, started, finished, options, format, input_bytes, input_key, "
    "input_faces, faces, \"overlaps\", result_kind, metrics, error, result_job, attempts, "
    "claimed_by, cancel_requested, progress, intermediate, "
    "(SELECT string_agg(r.name, '/') FROM results r WHERE r.job_id = result_job), tenant, expired";
constexpr int kColumnCount = 25;

// A running job held by a claim: $1 id, $2 node, $3 attempt.
constexpr const char* kHeld =
    "id = $1 AND claimed_by = $2 AND attempts = $3::int AND status = 'running'";

Params held(const std::string& id, const Claim& claim) {
  Params p;
  p.text(id).text(claim.node).number(std::int64_t{claim.attempt});
  return p;
}

JobRecord read_job(const Result& r, int row) {
  JobRecord j;
  j.seq = r.integer(row, 0);
  j.id = r.text(row, 1);
  j.status = parse_status(r.text(row, 2));
  j.created = r.real(row, 3);
  j.started = r.real(row, 4);
  j.finished = r.real(row, 5);
  j.options = nlohmann::json::parse(r.text(row, 6));
  j.format = r.text(row, 7);
  j.input_bytes = static_cast<std::size_t>(r.integer(row, 8));
  j.input_key = r.text(row, 9);
  j.input_faces = static_cast<std::size_t>(r.integer(row, 10));
  j.faces = static_cast<std::size_t>(r.integer(row, 11));
  j.overlaps = static_cast<std::size_t>(r.integer(row, 12));
  j.result_kind = r.text(row, 13);
  j.metrics = nlohmann::json::parse(r.text(row, 14));
  j.error = nlohmann::json::parse(r.text(row, 15));
  j.result_job = r.text(row, 16);
  j.attempts = static_cast<int>(r.integer(row, 17));
  j.node = r.text(row, 18);
  j.cancel_requested = r.boolean(row, 19);
  j.progress = nlohmann::json::parse(r.text(row, 20));
  j.intermediate = nlohmann::json::parse(r.text(row, 21));
  j.result_files = split_file_names(r.text(row, 22));
  j.tenant = r.text(row, 23);
  j.expired = r.boolean(row, 24);
  return j;
}

std::int64_t i64(std::size_t v) { return static_cast<std::int64_t>(v); }

void notify(Connection& c, const std::string& payload) {
  c.exec("SELECT pg_notify('papernet', $1)", Params().text(payload));
}

void put_files(Connection& c, const char* table, const std::string& id,
               const std::map<std::string, Artifact>& files) {
  for (const auto& [name, file] : files)
    c.exec(std::string("INSERT INTO ") + table +
               "(job_id, name, content_type, data) VALUES($1, $2, $3, $4::bytea) "
               "ON CONFLICT (job_id, name) DO UPDATE SET content_type = excluded.content_type, "
               "data = excluded.data",
           Params().text(id).text(name).text(file.content_type).bytes(file.data));
}

}  // namespace

PgJobStore::PgJobStore(const std::string& url, std::size_t connections)
    : url_(url), pool_(url, connections) {
  migrate();
}

PgJobStore::~PgJobStore() { listen({}); }

bool PgJobStore::insert(JobRecord& job, const JobInput* input, std::size_t queue_limit) {
  bool stored = false;
  pool_.run([&](Connection& c) {
    stored = c.transaction([&] {
      Result inserted = c.exec(
          "INSERT INTO jobs(id, status, created, started, finished, options, "
          "format, input_bytes, input_key, input_faces, faces, \"overlaps\", "
          "result_kind, metrics, error, result_job, attempts, tenant) VALUES($1, $2, "
          "$3::float8, $4::float8, $5::float8, $6, $7, $8::bigint, $9, $10::bigint, "
          "$11::bigint, $12::bigint, $13, $14, $15, $16, $17::int, $18) "
          "ON CONFLICT (id) DO NOTHING RETURNING seq",
          Params()
              .text(job.id)
              .text(status_name(job.status))
              .number(job.created)
              .number(job.started)
              .number(job.finished)
              .text(json_text(job.options))
              .text(job.format)
              .number(i64(job.input_bytes))
              .text(job.input_key)
              .number(i64(job.input_faces))
              .number(i64(job.faces))
              .number(i64(job.overlaps))
              .text(job.result_kind)
              .text(json_text(job.metrics))
              .text(json_text(job.error))
              .text(job.result_job)
              .number(std::int64_t{job.attempts})
              .text(job.tenant));
      if (inserted.rows() == 0) {  // a repetition after a lost connection: the first try stored it
        job.seq = c.exec("SELECT seq FROM jobs WHERE id = $1", Params().text(job.id)).integer(0, 0);
        return true;
      }
      job.seq = inserted.integer(0, 0);
      if (input) {
        c.exec("INSERT INTO inputs(job_id, mesh) VALUES($1, $2::bytea)",
               Params().text(job.id).bytes(input->mesh));
        for (const auto& [name, data] : input->external_files)
          c.exec("INSERT INTO input_files(job_id, name, data) VALUES($1, $2, $3::bytea)",
                 Params().text(job.id).text(name).bytes(data));
      }
      if (const auto url = job.options.find("callback_url");
          url != job.options.end() && url->is_string())
        c.exec("INSERT INTO webhooks(job_id, url) VALUES($1, $2)",
               Params().text(job.id).text(url->get<std::string>()));
      if (job.status != JobStatus::Queued) return true;
      // Nodes submitting at once count the queue one after the other, each with its own job
      // (the upload is stored by then, so the lock is held only for the count and the commit).
      c.exec("SELECT pg_advisory_xact_lock($1::bigint)", Params().number(kQueueLock));
      if (c.exec("SELECT count(*) FROM jobs WHERE status = 'queued'").integer(0, 0) >
          i64(queue_limit))
        return false;
      notify(c, "queued");
      return true;
    });
  });
  return stored;
}

std::optional<JobRecord> PgJobStore::find(const std::string& id) {
  std::optional<JobRecord> out;
  pool_.run([&](Connection& c) {
    Result r =
        c.exec(std::string("SELECT ") + kColumns + " FROM jobs WHERE id = $1", Params().text(id));
    if (r.rows() > 0) out = read_job(r, 0);
  });
  return out;
}

std::vector<JobRecord> PgJobStore::list(const std::string& tenant, std::size_t limit,
                                        std::int64_t before_seq) {
  std::vector<JobRecord> out;
  pool_.run([&](Connection& c) {
    Result r = c.exec(std::string("SELECT ") + kColumns +
                          " FROM jobs WHERE tenant = $3 AND NOT expired AND "
                          "($1::bigint = 0 OR seq < $1::bigint) "
                          "ORDER BY seq DESC LIMIT $2::bigint",
                      Params().number(before_seq).number(i64(limit)).text(tenant));
    out.clear();
    for (int i = 0; i < r.rows(); ++i) out.push_back(read_job(r, i));
  });
  return out;
}

JobInput PgJobStore::input(const std::string& id) {
  JobInput in;
  pool_.run([&](Connection& c) {
    const auto bytes = Connection::Format::Binary;
    Result mesh = c.exec(
        "SELECT i.mesh, j.format FROM inputs i JOIN jobs j ON j.id = i.job_id WHERE i.job_id = $1",
        Params().text(id), bytes);
    if (mesh.rows() == 0) throw StoreError("job store: no stored input for job " + id);
    in.mesh = mesh.text(0, 0);
    in.format = format_of_record(mesh.text(0, 1));
    Result files =
        c.exec("SELECT name, data FROM input_files WHERE job_id = $1", Params().text(id), bytes);
    in.external_files.clear();
    for (int i = 0; i < files.rows(); ++i) in.external_files[files.text(i, 0)] = files.text(i, 1);
  });
  return in;
}

std::optional<JobRecord> PgJobStore::find_reusable(const std::string& tenant,
                                                   const std::string& input_key,
                                                   const JobInput& input) {
  std::optional<JobRecord> out;
  pool_.run([&](Connection& c) {
    // The key is a hash; equal bytes make the match certain. External files are in the key.
    Result r = c.exec(std::string("SELECT ") + kColumns +
                          " FROM jobs JOIN inputs ON inputs.job_id = jobs.id WHERE input_key = $1 "
                          "AND status IN ('succeeded', 'approximated') AND inputs.mesh = "
                          "$2::bytea AND tenant = $3 ORDER BY seq DESC LIMIT 1",
                      Params().text(input_key).bytes(input.mesh).text(tenant));
    if (r.rows() > 0) out = read_job(r, 0);
  });
  return out;
}

IdempotencyRecord PgJobStore::remember_idempotency(const std::string& tenant,
                                                   const std::string& key,
                                                   const IdempotencyRecord& record, double since) {
  IdempotencyRecord out;
  pool_.run([&](Connection& c) {
    // A fresh record of the key stays (the update's WHERE fails, no row returned), a stale one
    // is replaced. When another request inserted the key concurrently, this statement waited
    // for it and returns nothing, and its snapshot predates that row: it is read by a statement
    // of its own. (A row forgotten in between: try again.)
    for (;;) {
      Result put = c.exec(
          "INSERT INTO idempotency(tenant, key, request_hash, job_id, created) "
          "VALUES($1, $2, $3, $4, $5::float8) ON CONFLICT (tenant, key) DO UPDATE SET "
          "request_hash = excluded.request_hash, job_id = excluded.job_id, created = "
          "excluded.created WHERE idempotency.created < $6::float8 RETURNING job_id",
          Params()
              .text(tenant)
              .text(key)
              .text(record.request_hash)
              .text(record.job_id)
              .number(record.created)
              .number(since));
      if (put.rows() > 0) {
        out = record;
        return;
      }
      Result earlier = c.exec(
          "SELECT request_hash, job_id, created FROM idempotency WHERE tenant = $1 AND key = $2",
          Params().text(tenant).text(key));
      if (earlier.rows() > 0) {
        out = {earlier.text(0, 0), earlier.text(0, 1), earlier.real(0, 2)};
        return;
      }
    }
  });
  return out;
}

void PgJobStore::forget_idempotency(const std::string& tenant, const std::string& key,
                                    const std::string& job_id) {
  pool_.run([&](Connection& c) {
    c.exec("DELETE FROM idempotency WHERE tenant = $1 AND key = $2 AND job_id = $3",
           Params().text(tenant).text(key).text(job_id));
  });
}

std::size_t PgJobStore::expire(double finished_before, double keys_before) {
  std::size_t expired = 0;
  pool_.run([&](Connection& c) {
    c.transaction([&] {
      expired = static_cast<std::size_t>(
          c.exec("WITH gone AS (UPDATE jobs SET expired = true WHERE NOT expired AND finished > 0 "
                 "AND finished < $1::float8 AND status IN ('succeeded', 'approximated', "
                 "'failed', 'cancelled') RETURNING 1) SELECT count(*) FROM gone",
                 Params().number(finished_before))
              .integer(0, 0));
      if (expired > 0)
        for (const char* table : {"inputs", "input_files", "intermediates"})
          c.exec(std::string("DELETE FROM ") + table +
                 " t USING jobs j WHERE j.id = t.job_id AND j.expired");
      // Also after earlier sweeps: a result kept for a job that reused it goes once that expired.
      c.exec(
          "DELETE FROM results r USING jobs j WHERE j.id = r.job_id AND j.expired AND NOT EXISTS "
          "(SELECT 1 FROM jobs k WHERE k.result_job = r.job_id AND NOT k.expired)");
      c.exec("DELETE FROM idempotency WHERE created < $1::float8", Params().number(keys_before));
      if (expired > 0)
        c.exec("DELETE FROM webhooks w USING jobs j WHERE j.id = w.job_id AND j.expired");
      return true;
    });
  });
  return expired;
}

std::uint64_t PgJobStore::stored_bytes() {
  std::uint64_t out = 0;
  // octet_length reads a value's length from its header, without decompressing it.
  pool_.run([&](Connection& c) {
    out = static_cast<std::uint64_t>(
        c.exec("SELECT (SELECT COALESCE(SUM(octet_length(mesh)), 0) FROM inputs) + "
               "(SELECT COALESCE(SUM(octet_length(data)), 0) FROM input_files) + "
               "(SELECT COALESCE(SUM(octet_length(data)), 0) FROM intermediates) + "
               "(SELECT COALESCE(SUM(octet_length(data)), 0) FROM results)")
            .integer(0, 0));
  });
  return out;
}

std::optional<double> PgJobStore::oldest_finished() {
  std::optional<double> out;
  pool_.run([&](Connection& c) {
    Result r = c.exec(
        "SELECT MIN(finished) FROM jobs WHERE NOT expired AND finished > 0 AND status IN "
        "('succeeded', 'approximated', 'failed', 'cancelled')");
    if (!r.null(0, 0)) out = r.real(0, 0);
  });
  return out;
}

std::size_t PgJobStore::queued_count(const std::string& tenant) {
  std::size_t out = 0;
  pool_.run([&](Connection& c) {
    out = static_cast<std::size_t>(
        c.exec("SELECT count(*) FROM jobs WHERE status = 'queued' AND tenant = $1",
               Params().text(tenant))
            .integer(0, 0));
  });
  return out;
}

std::map<std::string, std::size_t> PgJobStore::queued_by_tenant() {
  std::map<std::string, std::size_t> out;
  pool_.run([&](Connection& c) {
    Result r = c.exec("SELECT tenant, count(*) FROM jobs WHERE status = 'queued' GROUP BY tenant");
    out.clear();
    for (int i = 0; i < r.rows(); ++i)
      out[r.text(i, 0)] = static_cast<std::size_t>(r.integer(i, 1));
  });
  return out;
}

std::map<std::string, std::size_t> PgJobStore::count_by_status() {
  std::map<std::string, std::size_t> out;
  pool_.run([&](Connection& c) {
    Result r = c.exec("SELECT status, count(*) FROM jobs WHERE NOT expired GROUP BY status");
    for (int i = 0; i < r.rows(); ++i)
      out[r.text(i, 0)] = static_cast<std::size_t>(r.integer(i, 1));
  });
  return out;
}

std::size_t PgJobStore::queue_position(std::int64_t seq) {
  std::size_t out = 0;
  pool_.run([&](Connection& c) {
    out = static_cast<std::size_t>(
        c.exec("SELECT count(*) FROM jobs WHERE status = 'queued' AND seq <= $1::bigint",
               Params().number(seq))
            .integer(0, 0));
  });
  return out;
}

std::optional<ClaimedJob> PgJobStore::claim(const std::string& node, double lease_seconds,
                                            double started) {
  std::optional<ClaimedJob> out;
  pool_.run([&](Connection& c) {
    // One statement: the row is locked from the SELECT to the UPDATE, and a row another
    // worker holds locked is skipped rather than waited for.
    Result r = c.exec(
        std::string("WITH next AS (SELECT seq, status AS was, claimed_by AS was_node FROM jobs "
                    "WHERE status IN ('queued', 'running') AND (status = 'queued' OR "
                    "lease_until <= now()) ORDER BY seq LIMIT 1 FOR UPDATE SKIP LOCKED), "
                    "claimed AS (UPDATE jobs SET status = 'running', claimed_by = $1, "
                    "lease_until = now() + make_interval(secs => $2::float8), "
                    "attempts = attempts + 1, started = $3::float8, progress = 'null', "
                    "intermediate = 'null' FROM next WHERE jobs.seq = next.seq "
                    "RETURNING jobs.*, next.was, next.was_node), "
                    "stale AS (DELETE FROM intermediates USING claimed "
                    "WHERE intermediates.job_id = claimed.id) SELECT ") +
            kColumns + ", was, was_node, pg_notify('papernet', 'changed ' || id) FROM claimed",
        Params().text(node).number(lease_seconds).number(started));
    if (r.rows() == 0) return;
    out = ClaimedJob{read_job(r, 0), {}};
    if (r.text(0, kColumnCount) == "running") out->expired_node = r.text(0, kColumnCount + 1);
  });
  return out;
}

LeaseState PgJobStore::renew(const std::string& id, const Claim& claim, double lease_seconds,
                             const nlohmann::json* progress) {
  LeaseState state;
  pool_.run([&](Connection& c) {
    Params p = held(id, claim);
    p.number(lease_seconds);
    if (progress)
      p.text(progress->dump());
    else
      p.null();
    // A CTE that only selects runs when referenced: the notification goes out with new progress.
    Result r = c.exec(std::string("WITH renewed AS (UPDATE jobs SET lease_until = now() + "
                                  "make_interval(secs => $4::float8), progress = "
                                  "coalesce($5::text, progress) WHERE ") +
                          kHeld +
                          " RETURNING id, cancel_requested), told AS (SELECT pg_notify("
                          "'papernet', 'changed ' || id) FROM renewed WHERE $5::text IS NOT "
                          "NULL) SELECT cancel_requested, (SELECT count(*) FROM told) FROM renewed",
                      p);
    state = {};
    if (r.rows() > 0) state = {true, r.boolean(0, 0)};
  });
  return state;
}

bool PgJobStore::put_intermediate(const std::string& id, const Claim& claim,
                                  const JobOutput& output) {
  bool held_it = false;
  pool_.run([&](Connection& c) {
    held_it = c.transaction([&] {
      Params p = held(id, claim);
      p.text(json_text(intermediate_level_json(output)));
      if (c.exec(std::string("UPDATE jobs SET intermediate = $4 WHERE ") + kHeld + " RETURNING id",
                 p)
              .rows() == 0)
        return false;
      c.exec("DELETE FROM intermediates WHERE job_id = $1", Params().text(id));
      put_files(c, "intermediates", id, output.files);
      notify(c, "changed " + id);
      return true;
    });
  });
  return held_it;
}

std::optional<IntermediateFile> PgJobStore::intermediate(const std::string& id,
                                                         const std::string& name) {
  std::optional<IntermediateFile> out;
  pool_.run([&](Connection& c) {
    Result r = c.exec(
        "SELECT i.content_type, i.data, j.intermediate FROM intermediates i JOIN jobs j ON "
        "j.id = i.job_id WHERE i.job_id = $1 AND i.name = $2 AND j.status = 'running'",
        Params().text(id).text(name), Connection::Format::Binary);
    if (r.rows() == 0) return;
    if (const auto level = intermediate_level_from_json(nlohmann::json::parse(r.text(0, 2))))
      out = IntermediateFile{{r.text(0, 0), r.text(0, 1)}, level->faces, level->input_faces};
  });
  return out;
}

bool PgJobStore::finish(const JobRecord& job, const Claim& claim, const JobOutput* output) {
  bool held_it = false;
  pool_.run([&](Connection& c) {
    held_it = c.transaction([&] {
      Params p = held(job.id, claim);
      p.text(status_name(job.status))
          .number(job.finished)
          .number(i64(job.input_faces))
          .number(i64(job.faces))
          .number(i64(job.overlaps))
          .text(job.result_kind)
          .text(json_text(job.metrics))
          .text(json_text(job.error))
          .text(job.result_job);
      if (c.exec(std::string(
                     "UPDATE jobs SET status = $4, finished = $5::float8, "
                     "input_faces = $6::bigint, faces = $7::bigint, \"overlaps\" = $8::bigint, "
                     "result_kind = $9, metrics = $10, error = $11, result_job = $12, "
                     "lease_until = NULL, progress = 'null', intermediate = 'null' WHERE ") +
                     kHeld + " RETURNING id",
                 p)
              .rows() == 0)
        return false;
      if (output) put_files(c, "results", job.id, output->files);
      c.exec("DELETE FROM intermediates WHERE job_id = $1", Params().text(job.id));
      notify(c, "changed " + job.id);
      return true;
    });
  });
  return held_it;
}

bool PgJobStore::release(const std::string& id, const Claim& claim) {
  bool held_it = false;
  pool_.run([&](Connection& c) {
    held_it = c.transaction([&] {
      if (c.exec(std::string("UPDATE jobs SET status = 'queued', started = 0, claimed_by = '', "
                             "lease_until = NULL, progress = 'null', intermediate = 'null' "
                             "WHERE ") +
                     kHeld + " RETURNING id",
                 held(id, claim))
              .rows() == 0)
        return false;
      c.exec("DELETE FROM intermediates WHERE job_id = $1", Params().text(id));
      notify(c, "queued");
      notify(c, "changed " + id);
      return true;
    });
  });
  return held_it;
}

CancelOutcome PgJobStore::cancel(const std::string& id, const nlohmann::json& error,
                                 double finished) {
  CancelOutcome outcome = CancelOutcome::NotActive;
  pool_.run([&](Connection& c) {
    c.transaction([&] {
      outcome = CancelOutcome::NotActive;
      if (c.exec("UPDATE jobs SET status = 'cancelled', finished = $2::float8, error = $3 "
                 "WHERE id = $1 AND status = 'queued' RETURNING id",
                 Params().text(id).number(finished).text(json_text(error)))
              .rows() > 0) {
        outcome = CancelOutcome::Cancelled;
        notify(c, "changed " + id);
      } else if (c.exec("UPDATE jobs SET cancel_requested = true WHERE id = $1 AND "
                        "status = 'running' RETURNING id",
                        Params().text(id))
                     .rows() > 0) {
        outcome = CancelOutcome::Requested;
        notify(c, "cancel " + id);
        notify(c, "changed " + id);
      }
      return true;
    });
  });
  return outcome;
}

std::optional<Artifact> PgJobStore::artifact(const std::string& result_job,
                                             const std::string& name) {
  std::optional<Artifact> out;
  pool_.run([&](Connection& c) {
    Result r = c.exec("SELECT content_type, data FROM results WHERE job_id = $1 AND name = $2",
                      Params().text(result_job).text(name), Connection::Format::Binary);
    if (r.rows() > 0) out = Artifact{r.text(0, 0), r.text(0, 1)};
  });
  return out;
}

void PgJobStore::listen(std::function<void(const StoreEvent&)> on_event) {
  std::lock_guard lock(listener_mutex_);
  listener_.reset();
  if (!on_event) return;
  listener_ = std::make_unique<pg::Listener>(
      url_, "papernet",
      [on_event](const std::string& payload) {
        StoreEvent event;
        const auto space = payload.find(' ');
        const std::string kind = payload.substr(0, space);
        if (space != std::string::npos) event.job_id = payload.substr(space + 1);
        if (kind == "queued")
          event.kind = StoreEvent::Kind::Queued;
        else if (kind == "cancel")
          event.kind = StoreEvent::Kind::Cancel;
        on_event(event);
      },
      [on_event] {
        // Whatever was announced while the connection was away: look again at everything.
        on_event({StoreEvent::Kind::Queued, {}});
        on_event({StoreEvent::Kind::Changed, {}});
      });
}

void PgJobStore::ping() {
  pool_.run([](Connection& c) { c.exec("SELECT 1"); });
}

StoreStats PgJobStore::stats() {
  std::lock_guard lock(listener_mutex_);
  return {pool_.reconnects() + (listener_ ? listener_->reconnects() : 0)};
}

}  // namespace papernet::server
