// The PostgreSQL store's schema, version by version, and its migration when a store opens
// (PgJobStore::migrate): the tables, indexes and storage settings its queries (pg_store.cpp,
// pg_webhooks.cpp) rely on.
#include <cstdint>
#include <iterator>
#include <string>

#include "server/pg_store.h"

namespace papernet::server {
namespace {

using pg::Connection;
using pg::Params;

// The schema's versions, applied in order; papernet_schema records the applied ones. A new
// version is a new entry at the end, never an edit of an applied one.
constexpr const char* kMigrations[] = {
    R"sql(
CREATE TABLE jobs(
  seq bigint GENERATED ALWAYS AS IDENTITY PRIMARY KEY,
  id text UNIQUE NOT NULL,
  status text NOT NULL,
  created double precision NOT NULL,
  started double precision NOT NULL DEFAULT 0,
  finished double precision NOT NULL DEFAULT 0,
  options text NOT NULL, format text NOT NULL, input_bytes bigint NOT NULL,
  input_key text NOT NULL, input_faces bigint NOT NULL DEFAULT 0,
  faces bigint NOT NULL DEFAULT 0, "overlaps" bigint NOT NULL DEFAULT 0,
  result_kind text NOT NULL DEFAULT '', metrics text NOT NULL DEFAULT '{}',
  error text NOT NULL DEFAULT 'null', result_job text NOT NULL DEFAULT '',
  attempts integer NOT NULL DEFAULT 0,
  claimed_by text NOT NULL DEFAULT '',
  lease_until timestamptz,
  cancel_requested boolean NOT NULL DEFAULT false,
  progress text NOT NULL DEFAULT 'null',
  intermediate text NOT NULL DEFAULT 'null');
-- ("overlaps" is a keyword in PostgreSQL.) The queue: what a worker may claim, in submission order.
CREATE INDEX jobs_unfinished ON jobs(seq) WHERE status IN ('queued', 'running');
CREATE INDEX jobs_by_key ON jobs(input_key);
CREATE TABLE inputs(job_id text PRIMARY KEY REFERENCES jobs(id) ON DELETE CASCADE,
  mesh bytea NOT NULL);
CREATE TABLE input_files(job_id text NOT NULL REFERENCES jobs(id) ON DELETE CASCADE,
  name text NOT NULL, data bytea NOT NULL, PRIMARY KEY(job_id, name));
CREATE TABLE results(job_id text NOT NULL REFERENCES jobs(id) ON DELETE CASCADE,
  name text NOT NULL, content_type text NOT NULL, data bytea NOT NULL,
  PRIMARY KEY(job_id, name));
CREATE TABLE intermediates(job_id text NOT NULL REFERENCES jobs(id) ON DELETE CASCADE,
  name text NOT NULL, content_type text NOT NULL, data bytea NOT NULL,
  PRIMARY KEY(job_id, name));
-- Rewritten every few seconds while a job runs: not worth compressing.
ALTER TABLE intermediates ALTER COLUMN data SET STORAGE EXTERNAL;
-- lz4 compresses uploads and results at a fraction of the default pglz's CPU (a server built
-- without lz4 keeps pglz).
DO $$ BEGIN
  ALTER TABLE inputs ALTER COLUMN mesh SET COMPRESSION lz4;
  ALTER TABLE input_files ALTER COLUMN data SET COMPRESSION lz4;
  ALTER TABLE results ALTER COLUMN data SET COMPRESSION lz4;
EXCEPTION WHEN feature_not_supported THEN NULL;
END $$;
)sql",
    // Tenants (API keys): a job belongs to the tenant that submitted it.
    R"sql(
ALTER TABLE jobs ADD COLUMN tenant text NOT NULL DEFAULT '';
CREATE INDEX jobs_by_tenant ON jobs(tenant, seq);
)sql",
    // Idempotency-Key: per tenant, what a key stood for (24 h).
    R"sql(
CREATE TABLE idempotency(tenant text NOT NULL, key text NOT NULL,
  request_hash text NOT NULL, job_id text NOT NULL, created double precision NOT NULL,
  PRIMARY KEY(tenant, key));
)sql",
    // Retention: an expired job keeps its row (410), not its input or files.
    R"sql(
ALTER TABLE jobs ADD COLUMN expired boolean NOT NULL DEFAULT false;
)sql",
    // Webhooks: a job's callback delivery, kept until it is done so that a restart resumes it.
    R"sql(
CREATE TABLE webhooks(job_id text PRIMARY KEY REFERENCES jobs(id) ON DELETE CASCADE,
  url text NOT NULL, state text NOT NULL DEFAULT 'pending', attempts text NOT NULL DEFAULT '[]',
  next_at double precision NOT NULL DEFAULT 0, claimed_by text NOT NULL DEFAULT '',
  lease_until double precision NOT NULL DEFAULT 0);
CREATE INDEX webhooks_pending ON webhooks(next_at) WHERE state = 'pending';
)sql",
};

// Advisory lock key: one migration at a time (pg_store.cpp's queue lock is another).
constexpr std::int64_t kSchemaLock = 0x7061706572'01;

}  // namespace

int PgJobStore::schema_version() { return static_cast<int>(std::size(kMigrations)); }

void PgJobStore::migrate() {
  pool_.run([&](Connection& c) {
    // Session-level: held until unlocked, or until a lost connection drops it.
    c.exec("SELECT pg_advisory_lock($1::bigint)", Params().number(kSchemaLock));
    c.exec_script(
        "CREATE TABLE IF NOT EXISTS papernet_schema(version integer PRIMARY KEY, "
        "applied timestamptz NOT NULL DEFAULT now())");
    const auto version = static_cast<int>(
        c.exec("SELECT coalesce(max(version), 0) FROM papernet_schema").integer(0, 0));
    try {
      if (version > schema_version())
        throw StoreError("job store: the database has schema version " + std::to_string(version) +
                         ", newer than this papernet knows (" + std::to_string(schema_version()) +
                         "); upgrade papernet");
      for (int v = version + 1; v <= schema_version(); ++v)
        c.transaction([&] {
          c.exec_script(kMigrations[v - 1]);
          c.exec("INSERT INTO papernet_schema(version) VALUES($1::int)",
                 Params().number(std::int64_t{v}));
          return true;
        });
    } catch (...) {
      if (!c.broken())
        c.exec("SELECT pg_advisory_unlock($1::bigint)", Params().number(kSchemaLock));
      throw;
    }
    c.exec("SELECT pg_advisory_unlock($1::bigint)", Params().number(kSchemaLock));
  });
}

}  // namespace papernet::server
