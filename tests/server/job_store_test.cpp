// The stores' queue on its own: claims in submission order, each job to one worker however many
// race for it, leases that expire, claims that fence what a former holder writes, and the
// schema migrations (several nodes starting at once; a file from before versioning).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <set>
#include <thread>

#include "server/pg_store.h"
#include "server/sqlite_store.h"
#include "tests/support/postgres.h"

using namespace papernet;
using namespace papernet::server;
using papernet::test::BothStores;

namespace {

class JobStoreTest : public BothStores {};
INSTANTIATE_BOTH_STORES(JobStoreTest);

std::string add_job(JobStore& store, int n) {
  JobRecord job;
  job.id = new_job_id();
  job.created = now_seconds();
  job.options = options_to_json({});
  job.format = "obj";
  job.input_key = "key" + std::to_string(n);
  JobInput input;
  input.mesh = "v 0 0 " + std::to_string(n) + "\n";
  input.format = MeshFormat::Obj;
  EXPECT_TRUE(store.insert(job, &input, 1000));
  return job.id;
}

}  // namespace

TEST_P(JobStoreTest, WorkersRacingForJobsClaimEachOnceInSubmissionOrder) {
  const auto store = open_store();
  std::vector<std::string> ids;
  for (int i = 0; i < 40; ++i) ids.push_back(add_job(*store, i));
  EXPECT_EQ(store->queue_position(store->find(ids[3])->seq), 4u);
  // Four nodes' workers, each with a store (a connection pool) of its own, claim until none is
  // left: every job exactly once.
  std::vector<std::unique_ptr<JobStore>> nodes;
  for (int n = 0; n < 4; ++n) nodes.push_back(postgres() ? open_store() : nullptr);
  std::mutex mutex;
  std::vector<std::string> claimed;
  std::vector<std::thread> workers;
  for (int n = 0; n < 4; ++n)
    workers.emplace_back([&, n] {
      JobStore& mine = nodes[n] ? *nodes[n] : *store;
      while (auto job = mine.claim("node" + std::to_string(n), 30, now_seconds())) {
        std::lock_guard lock(mutex);
        claimed.push_back(job->record.id);
      }
    });
  for (std::thread& t : workers) t.join();
  EXPECT_EQ(claimed.size(), ids.size());
  EXPECT_EQ(std::set<std::string>(claimed.begin(), claimed.end()).size(), ids.size());
  EXPECT_EQ(store->count_by_status()["running"], 40u);
  EXPECT_FALSE(store->claim("late", 30, now_seconds())) << "leases still run";
}

TEST_P(JobStoreTest, AnExpiredLeaseIsClaimedAgainAndFencesItsFormerHolder) {
  const auto store = open_store();
  const std::string id = add_job(*store, 1);
  const ClaimedJob first = *store->claim("node-a", 0, now_seconds());  // expires at once
  EXPECT_EQ(first.record.attempts, 1);
  EXPECT_EQ(first.expired_node, "");
  const Claim a{"node-a", 1};
  const std::optional<ClaimedJob> second = store->claim("node-b", 30, now_seconds());
  ASSERT_TRUE(second);
  EXPECT_EQ(second->record.id, id);
  EXPECT_EQ(second->expired_node, "node-a");
  EXPECT_EQ(second->record.attempts, 2);
  const Claim b{"node-b", 2};

  // Node a, back from a long pause, learns it lost the job: nothing it writes lands.
  const nlohmann::json progress = {{"phase", "unfold"}};
  EXPECT_FALSE(store->renew(id, a, 30, &progress).held);
  JobOutput output;
  output.files["net.json"] = {"application/json", "{\"from\":\"a\"}"};
  EXPECT_FALSE(store->put_intermediate(id, a, output));
  JobRecord ended = second->record;
  ended.status = JobStatus::Succeeded;
  ended.result_job = id;
  EXPECT_FALSE(store->finish(ended, a, &output));
  EXPECT_FALSE(store->release(id, a));
  EXPECT_TRUE(store->find(id)->progress.is_null());

  // Node b holds it: its progress, its intermediate and its end are the job's.
  const LeaseState held = store->renew(id, b, 30, &progress);
  EXPECT_TRUE(held.held);
  EXPECT_FALSE(held.cancel_requested);
  EXPECT_EQ(store->find(id)->progress["phase"], "unfold");
  output.files["net.json"].data = "{\"from\":\"b\"}";
  EXPECT_TRUE(store->put_intermediate(id, b, output));
  EXPECT_EQ(store->intermediate(id, "net.json")->file.data, "{\"from\":\"b\"}");
  EXPECT_EQ(store->cancel(id, nullptr, now_seconds()), CancelOutcome::Requested);
  EXPECT_TRUE(store->renew(id, b, 30, nullptr).cancel_requested);
  EXPECT_TRUE(store->finish(ended, b, &output));
  EXPECT_EQ(store->find(id)->status, JobStatus::Succeeded);
  EXPECT_EQ(store->artifact(id, "net.json")->data, "{\"from\":\"b\"}");
  EXPECT_FALSE(store->intermediate(id, "net.json")) << "a finished job has no intermediate";
  EXPECT_EQ(store->cancel(id, nullptr, now_seconds()), CancelOutcome::NotActive);
}

TEST_P(JobStoreTest, TheQueueLimitCountsQueuedJobsOnly) {
  const auto store = open_store();
  add_job(*store, 1);
  add_job(*store, 2);
  JobRecord third;
  third.id = new_job_id();
  third.options = options_to_json({});
  EXPECT_FALSE(store->insert(third, nullptr, 2)) << "two are queued";
  EXPECT_FALSE(store->find(third.id));
  ASSERT_TRUE(store->claim("node", 30, now_seconds()));
  EXPECT_TRUE(store->insert(third, nullptr, 2)) << "one runs, one is queued";
}

// Idempotency-Key (README): a key stands for its first request within the window (the service
// passes `since` = now - 24 h), per tenant; a record older than the window gives way.
TEST_P(JobStoreTest, AnIdempotencyKeyStandsForItsFirstRequestWithinTheWindowOnly) {
  const auto store = open_store();
  constexpr double kDay = 24 * 3600;
  const double t0 = 1'000'000;
  EXPECT_EQ(store->remember_idempotency("shop-a", "k", {"h1", "job1", t0}, t0 - kDay).job_id,
            "job1");
  // The same key an hour later, even with another request: the first stands.
  const IdempotencyRecord again =
      store->remember_idempotency("shop-a", "k", {"h2", "job2", t0 + 3600}, t0 + 3600 - kDay);
  EXPECT_EQ(again.job_id, "job1");
  EXPECT_EQ(again.request_hash, "h1");
  // Another tenant's key of the same name is its own.
  EXPECT_EQ(store->remember_idempotency("shop-b", "k", {"h3", "job3", t0 + 3600}, t0 + 3600 - kDay)
                .job_id,
            "job3");
  // A day and a second after the first: it no longer stands; the new request takes the key.
  const double later = t0 + kDay + 1;
  EXPECT_EQ(store->remember_idempotency("shop-a", "k", {"h4", "job4", later}, later - kDay).job_id,
            "job4");
  EXPECT_EQ(store->remember_idempotency("shop-a", "k", {"h5", "job5", later}, later - kDay).job_id,
            "job4");
  // Retention's sweep drops records created before its cut-off.
  store->expire(0, later + 1);
  EXPECT_EQ(store->remember_idempotency("shop-a", "k", {"h6", "job6", later + 2}, 0).job_id,
            "job6");
}

// Several nodes start at once on an empty database: the schema is migrated once.
TEST(PgStoreMigrations, NodesStartingTogetherMigrateOnceAndANewerSchemaIsRefused) {
  PAPERNET_SHARED_POSTGRES(postgres);
  const std::string database = postgres->create_database();
  std::vector<std::thread> nodes;
  std::atomic<int> failed{0};
  for (int i = 0; i < 6; ++i)
    nodes.emplace_back([&] {
      try {
        PgJobStore store(postgres->url(database), 2);
      } catch (const StoreError& e) {
        ++failed;
        ADD_FAILURE() << e.what();
      }
    });
  for (std::thread& t : nodes) t.join();
  EXPECT_EQ(failed, 0);
  EXPECT_EQ(postgres->query(database, "SELECT count(*) FROM papernet_schema"),
            std::to_string(PgJobStore::schema_version()));
  postgres->query(database, "INSERT INTO papernet_schema(version) VALUES (99)");
  try {
    PgJobStore store(postgres->url(database), 2);
    ADD_FAILURE() << "opened a database of a newer papernet";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("schema version 99, newer than this papernet"),
              std::string::npos)
        << e.what();
  }
  postgres->drop_database(database);
}

// A store file written before the schema had versions (PRAGMA user_version 0) keeps its jobs
// and gains the columns of leases and progress.
TEST(SqliteStoreMigrations, AFileFromBeforeVersioningIsMigrated) {
  const auto dir = std::filesystem::temp_directory_path() / ("papernet_old_" + new_job_id());
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "papernet.sqlite").string();
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(
      sqlite3_exec(db,
                   "CREATE TABLE jobs(seq INTEGER PRIMARY KEY AUTOINCREMENT, id TEXT UNIQUE "
                   "NOT NULL, status TEXT NOT NULL, created REAL NOT NULL, started REAL NOT "
                   "NULL DEFAULT 0, finished REAL NOT NULL DEFAULT 0, options TEXT NOT NULL, "
                   "format TEXT NOT NULL, input_bytes INTEGER NOT NULL, input_key TEXT NOT "
                   "NULL, input_faces INTEGER NOT NULL DEFAULT 0, faces INTEGER NOT NULL "
                   "DEFAULT 0, overlaps INTEGER NOT NULL DEFAULT 0, result_kind TEXT NOT "
                   "NULL DEFAULT '', metrics TEXT NOT NULL DEFAULT '{}', error TEXT NOT NULL "
                   "DEFAULT 'null', result_job TEXT NOT NULL DEFAULT '', attempts INTEGER "
                   "NOT NULL DEFAULT 0);"
                   "CREATE TABLE inputs(job_id TEXT PRIMARY KEY, mesh BLOB NOT NULL);"
                   "INSERT INTO jobs(id, status, created, options, format, input_bytes, "
                   "input_key, attempts) VALUES('0123456789abcdef0123456789abcdef', "
                   "'running', 1, '{}', 'obj', 9, 'k', 1);"
                   "INSERT INTO inputs VALUES('0123456789abcdef0123456789abcdef', 'v 0 0 0');",
                   nullptr, nullptr, nullptr),
      SQLITE_OK);
  sqlite3_close(db);
  {
    SqliteJobStore store(path);
    EXPECT_EQ(store.recover_interrupted(),
              std::vector<std::string>{"0123456789abcdef0123456789abcdef"});
    const auto job = store.claim("node", 30, now_seconds());
    ASSERT_TRUE(job);
    EXPECT_EQ(job->record.attempts, 2);
    EXPECT_EQ(store.input(job->record.id).mesh, "v 0 0 0");
  }
  SqliteJobStore again(path);  // opening a migrated file changes nothing
  EXPECT_EQ(again.find("0123456789abcdef0123456789abcdef")->node, "node");
  std::filesystem::remove_all(dir);
}

// A callback is due once its job ended, goes to one node at a time, waits for its next_at, and
// a node whose claim passed on cannot overwrite it.
TEST_P(JobStoreTest, ACallbackIsDueWhenItsJobEndsAndOneNodeHoldsItAtATime) {
  const auto store = open_store();
  const auto other = postgres() ? open_store() : nullptr;
  JobStore& second = other ? *other : *store;
  JobOptions options;
  options.callback_url = "http://hooks.example/papernet";
  JobRecord job;
  job.id = new_job_id();
  job.created = now_seconds();
  job.options = options_to_json(options);
  job.format = "obj";
  job.input_key = "hooked";
  JobInput input;
  input.mesh = "v 0 0 0\n";
  ASSERT_TRUE(store->insert(job, &input, 1000));
  const std::string plain = add_job(*store, 1);
  EXPECT_FALSE(store->webhook(plain)) << "no callback_url, no delivery";
  const std::optional<WebhookDelivery> made = store->webhook(job.id);
  ASSERT_TRUE(made);
  EXPECT_EQ(made->url, "http://hooks.example/papernet");
  EXPECT_EQ(made->state, "pending");
  EXPECT_TRUE(made->attempts.empty());
  const double now = now_seconds();
  EXPECT_FALSE(store->claim_webhook("a", now, 30)) << "its job has not ended";

  auto running = store->claim("worker", 30, now);
  ASSERT_TRUE(running);
  ASSERT_EQ(running->record.id, job.id);
  JobRecord ended = running->record;
  ended.status = JobStatus::Failed;
  ended.finished = now_seconds();
  ended.error = {{"code", "unfold_failed"}};
  ASSERT_TRUE(store->finish(ended, {"worker", running->record.attempts}, nullptr));

  std::optional<WebhookDelivery> held = store->claim_webhook("a", now_seconds(), 30);
  ASSERT_TRUE(held);
  EXPECT_EQ(held->job_id, job.id);
  EXPECT_FALSE(second.claim_webhook("b", now_seconds(), 30)) << "node a holds it";
  WebhookDelivery tried = *held;
  tried.attempts.push_back({{"at", now_seconds()}, {"status", 500}});
  tried.next_at = now_seconds() + 100;
  EXPECT_FALSE(second.update_webhook(tried, "b")) << "b never held it";
  EXPECT_TRUE(store->update_webhook(tried, "a"));
  EXPECT_FALSE(second.claim_webhook("b", now_seconds(), 30)) << "not due before next_at";
  held = second.claim_webhook("b", now_seconds() + 101, 30);
  ASSERT_TRUE(held);
  EXPECT_EQ(held->attempts.size(), 1u);
  EXPECT_EQ(held->attempts[0]["status"], 500);
  held->state = "delivered";
  held->attempts.push_back({{"at", now_seconds()}, {"status", 200}});
  EXPECT_TRUE(second.update_webhook(*held, "b"));
  EXPECT_FALSE(store->claim_webhook("a", now_seconds() + 1e6, 30)) << "delivered is done";
  EXPECT_EQ(store->webhook(job.id)->state, "delivered");
  EXPECT_EQ(store->webhook(job.id)->attempts.size(), 2u);
}
