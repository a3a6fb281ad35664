// Several `papernet serve` nodes sharing one PostgreSQL store (docs/scaling.md): every node
// answers for every job, a killed node's jobs finish elsewhere, no job completes twice, the
// database may restart under running jobs, and a job that kills every node stops being retried.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <regex>
#include <set>

#include "tests/support/files.h"
#include "tests/support/paths.h"
#include "tests/support/sanitized.h"
#include "tests/support/serve_http.h"
#include "tests/support/serve_process.h"

using namespace papernet::test;

namespace {

// A tetrahedron; `n` makes each upload distinct, so no job reuses another's result.
std::string tetra(int n) {
  return "# job " + std::to_string(n) +
         "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
}

// The runs a node completed, by job id, from its log ("job ID running -> succeeded ...").
std::map<std::string, int> completions(const std::string& log) {
  static const std::regex line("job ([0-9a-f]{32}) running -> (succeeded|approximated)");
  std::map<std::string, int> out;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), line); it != std::sregex_iterator();
       ++it)
    ++out[(*it)[1]];
  return out;
}

// True once the node's log says it started running the job.
bool runs(const Server& node, const std::string& id) {
  return node.log().find("job " + id + " queued -> running") != std::string::npos ||
         node.log().find("job " + id + " running -> running") != std::string::npos;
}

bool wait_until(const std::function<bool()>& condition, std::chrono::seconds limit) {
  for (const auto end = std::chrono::steady_clock::now() + limit;
       std::chrono::steady_clock::now() < end; std::this_thread::sleep_for(20ms))
    if (condition()) return true;
  return condition();
}

// A node stores a job's end before it logs it, so a client can read the job's final status
// before the line is there: waits (at most 10 s) until each of `ids` has a completion line in
// `logs()`.
void await_logged(const std::vector<std::string>& ids, const std::function<std::string()>& logs) {
  wait_until(
      [&] {
        const auto done = completions(logs());
        return std::all_of(ids.begin(), ids.end(),
                           [&](const std::string& id) { return done.count(id) > 0; });
      },
      10s);
}

// The events a node streams for a job until `enough` says so (or the stream ends).
std::string stream_events(const Server& node, const std::string& id,
                          const std::function<bool(const std::string&)>& enough) {
  std::string text;
  auto c = node.client();
  c.set_read_timeout(10, 0);
  c.Get("/v1/jobs/" + id + "/events", [&](const char* data, std::size_t n) {
    text.append(data, n);
    return !enough(text);
  });
  return text;
}

// `papernet serve ARGS`, which is expected to fail: its exit code and what it printed. A serve
// that starts after all is stopped after 20 s (and the test fails on its exit code).
int papernet_serve(const std::string& args, std::string* output) {
  FILE* p = popen(
      ("timeout 20 " + papernet::test::papernet_binary() + " serve " + args + " 2>&1").c_str(),
      "r");
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) output->append(buf, n);
  const int status = pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

double metric(const Server& node, const std::string& name) {
  const std::string text = node.client().Get("/metrics")->body;
  const auto at = text.find("\n" + name + " ");
  return at == std::string::npos ? -1 : std::stod(text.substr(at + name.size() + 2));
}

class MultiNode : public testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    postgres_ = PostgresServer::shared(&why);
    if (!postgres_) GTEST_SKIP() << "PostgreSQL is not installed, so this test skips: " << why;
    database_ = postgres_->create_database();
  }
  void TearDown() override {
    if (postgres_) postgres_->drop_database(database_);
  }
  // A node on the test's database with short leases (a killed node's job runs again soon).
  std::vector<std::string> node(std::vector<std::string> flags, const std::string& lease = "2") {
    flags.insert(flags.begin(), {"--store", postgres_->url(database_), "--lease", lease});
    return flags;
  }
  PostgresServer* postgres_ = nullptr;
  std::string database_;
};

}  // namespace

// 20 jobs go to node A, some large; A is killed with kill -9 while it runs one of them. Node B
// answers every status, stream and result, runs what A left, and each job completes once.
TEST_F(MultiNode, KillNineMidJobAndTheOtherNodeFinishesEveryJob) {
  auto a = std::make_unique<Server>(node({"--workers", "2"}));
  std::vector<std::string> ids, large;
  for (int i = 0; i < 20; ++i) {
    // Two large jobs (A runs two at a time): 4,212 faces; tiled, the print is not what this test
    // is about. Four of them took most of its two minutes under ASan.
    if (i % 10 == 0) {
      large.push_back(
          submit(*a, test_mesh("Duck.glb"), "model/gltf-binary",
                 "?detail=full&strategy=TU&tab_room_budget=0&colour=none&layout=tile&seed=" +
                     std::to_string(i + 1)));
      ids.push_back(large.back());
    } else if (i % 5 == 1) {
      // Collapsed to what prints at 200 mm (276 of 1,000 faces), and tiled: its print is not
      // what this test is about either (the fit search took 9 of its 10 s under ASan).
      ids.push_back(submit(*a, test_mesh("sample.obj"), "model/obj",
                           "?tab_room_budget=0&layout=tile&seed=" + std::to_string(i + 1)));
    } else {
      ids.push_back(submit(*a, tetra(i), "model/obj", "?strategy=TU"));
    }
  }
  Server b(node({"--workers", "1"}));
  // Every node answers for every job, and B streams the progress of A's first job.
  for (const std::string& id : ids) {
    EXPECT_EQ(a->client().Get("/v1/jobs/" + id)->status, 200);
    EXPECT_EQ(b.client().Get("/v1/jobs/" + id)->status, 200);
  }
  const std::string events = stream_events(b, ids[0], [](const std::string& text) {
    return text.find("\"phase\":\"unfold\"") != std::string::npos ||
           text.find("event: done") != std::string::npos;
  });
  EXPECT_NE(events.find("event: progress"), std::string::npos) << events;

  // Kill A while it runs a large job.
  std::string victim;
  ASSERT_TRUE(wait_until(
      [&] {
        const auto done = completions(a->log());
        for (const std::string& id : large)
          if (runs(*a, id) && done.count(id) == 0) {
            victim = id;
            return true;
          }
        return false;
      },
      60s))
      << "node A never ran a large job\n"
      << a->log();
  EXPECT_TRUE(WIFSIGNALED(a->stop(SIGKILL)));
  const std::string a_log = a->log();
  a.reset();

  for (const std::string& id : ids) {
    const json job = wait_final(b, id, 180);
    EXPECT_TRUE(job["status"] == "succeeded" || job["status"] == "approximated") << job.dump();
    auto net = b.client().Get("/v1/jobs/" + id + "/net.json");
    ASSERT_TRUE(net);
    EXPECT_EQ(net->status, 200) << id;
  }
  const std::string done = stream_events(b, victim, [](const std::string&) { return false; });
  EXPECT_NE(done.find("event: done"), std::string::npos) << done;

  // Each job completed exactly once, on A before the kill or on B.
  await_logged(ids, [&] { return a_log + b.log(); });
  const auto on_a = completions(a_log), on_b = completions(b.log());
  int twice = 0, never = 0;
  for (const std::string& id : ids) {
    const int n = (on_a.count(id) ? on_a.at(id) : 0) + (on_b.count(id) ? on_b.at(id) : 0);
    twice += n > 1;
    never += n == 0;
  }
  std::cout << "[ figures  ] 20 jobs: " << on_a.size() << " completed on A before its kill, "
            << on_b.size() << " on B; completed twice: " << twice << ", never: " << never
            << "; B took over " << metric(b, "papernet_store_lease_expiries_total")
            << " expired leases\n";
  EXPECT_EQ(twice, 0);
  EXPECT_EQ(never, 0);
  EXPECT_EQ(on_a.count(victim), 0u);
  EXPECT_NE(b.log().find("job " + victim + " running -> running (the lease of"), std::string::npos)
      << b.log();
  EXPECT_GE(metric(b, "papernet_store_lease_expiries_total"), 1);
}

// A job runs on A; B, started later, shows its progress and serves its intermediate nets, and
// a cancel sent to B stops it on A within a second (NOTIFY, or the lease keeper's poll).
TEST_F(MultiNode, OtherNodesShowProgressServeIntermediatesAndCancelWithinASecond) {
  Server a(node({"--workers", "1"}));
  const std::string id =
      submit(a, test_mesh("Duck.glb"), "model/gltf-binary", "?detail=full&strategy=QQ&colour=none");
  wait_running(a, id);
  Server b(node({"--workers", "1"}));
  auto c = b.client();
  bool intermediate = false;
  ASSERT_TRUE(wait_until(
      [&] {
        auto res = c.Get("/v1/jobs/" + id + "/net.json");
        intermediate = res && res->status == 200 &&
                       res->get_header_value("X-Papernet-Level").rfind("intermediate", 0) == 0;
        return intermediate || body(c.Get("/v1/jobs/" + id))["status"] != "running";
      },
      60s));
  ASSERT_TRUE(intermediate) << "B served no intermediate of A's job";
  const json seen = body(c.Get("/v1/jobs/" + id));
  EXPECT_EQ(seen["status"], "running");
  EXPECT_TRUE(seen["progress"]["phase"].is_string()) << seen.dump();
  EXPECT_TRUE(seen["links"].contains("net.json")) << seen.dump();
  EXPECT_EQ(a.log().find("job " + id + " running ->"), std::string::npos) << "still on A";

  const auto before = std::chrono::steady_clock::now();
  EXPECT_EQ(c.Delete("/v1/jobs/" + id)->status, 202);
  std::string status;
  while (std::chrono::steady_clock::now() - before < 5s &&
         (status = body(c.Get("/v1/jobs/" + id))["status"]) == "running")
    std::this_thread::sleep_for(5ms);
  const auto took = std::chrono::steady_clock::now() - before;
  std::cout << "[ figures  ] cancel sent to B, job cancelled on A after "
            << std::chrono::duration<double>(took).count() << " s\n";
  EXPECT_EQ(status, "cancelled");
#ifdef PAPERNET_TEST_SANITIZED
  // Sanitized, the job's steps between two looks at the cancel run ten times slower: under ASan
  // on 2026-11-29 the cancel landed after 3.83, 3.73 and 0.04 s, by what node A was doing.
  EXPECT_LT(took, 6s);
#else
  EXPECT_LT(took, 1s);
#endif
  // A logs the end just after storing it, where B may see it first (a CI run read A's log in
  // between, 2026-12-02).
  EXPECT_TRUE(wait_until(
      [&] { return a.log().find("job " + id + " running -> cancelled") != std::string::npos; }, 5s))
      << a.log();
  expect_problem(c.Get("/v1/jobs/" + id + "/net.json"), 410, "job_cancelled");
}

// The queue limit counts every node's queue, and a result computed on one node answers an
// identical job submitted to another.
TEST_F(MultiNode, TheQueueLimitAndResultReuseSpanNodes) {
  const std::vector<std::string> flags = node({"--workers", "1", "--queue-length", "2"});
  Server a(flags), b(flags);
  std::vector<std::string> busy;
  for (int seed = 1; seed <= 2; ++seed)
    busy.push_back(submit(a, test_mesh("Duck.glb"), "model/gltf-binary",
                          "?detail=full&strategy=TU&colour=none&seed=" + std::to_string(seed)));
  ASSERT_TRUE(wait_until(
      [&] {
        return body(b.client().Get("/v1/jobs/" + busy[0]))["status"] == "running" &&
               body(b.client().Get("/v1/jobs/" + busy[1]))["status"] == "running";
      },
      30s))
      << "both workers (one per node) should run one job each";
  const std::string q1 = submit(a, tetra(1), "model/obj");
  const std::string q2 = submit(b, tetra(2), "model/obj");
  expect_problem(b.client().Post("/v1/jobs", tetra(3), "model/obj"), 429, "queue_full");
  expect_problem(a.client().Post("/v1/jobs", tetra(3), "model/obj"), 429, "queue_full");
  EXPECT_EQ(body(a.client().Get("/v1/jobs/" + q2))["progress"]["queue_position"], 2);
  for (const std::string& id : busy) b.client().Delete("/v1/jobs/" + id);
  for (const std::string& id : {q1, q2}) EXPECT_EQ(wait_final(a, id)["status"], "succeeded");

  const json again = body(b.client().Post("/v1/jobs", tetra(1), "model/obj"));
  EXPECT_EQ(again["status"], "succeeded") << again.dump();
  EXPECT_EQ(again["result"]["metrics"]["reused_from"], q1);
  EXPECT_EQ(b.client().Get("/v1/jobs/" + again["id"].get<std::string>() + "/net.json")->body,
            a.client().Get("/v1/jobs/" + q1 + "/net.json")->body);
}

// A mesh that kills every node that runs it (here the test kills them) is not retried forever:
// after --max-attempts claims it fails with interrupted_too_often, saying why.
TEST_F(MultiNode, AJobThatKillsEveryNodeFailsAfterItsAttempts) {
  const std::vector<std::string> flags = node({"--workers", "1", "--max-attempts", "2"}, "1");
  std::string id;
  for (int attempt = 1; attempt <= 2; ++attempt) {
    Server victim(flags);
    if (id.empty())
      id = submit(victim, test_mesh("Duck.glb"), "model/gltf-binary",
                  "?detail=full&strategy=TU&colour=none");
    ASSERT_TRUE(wait_until([&] { return runs(victim, id); }, 30s)) << victim.log();
    EXPECT_TRUE(WIFSIGNALED(victim.stop(SIGKILL)));
  }
  Server last(flags);
  const json job = wait_final(last, id, 30);
  EXPECT_EQ(job["status"], "failed");
  EXPECT_EQ(job["error"]["code"], "interrupted_too_often") << job.dump();
  EXPECT_NE(job["error"]["detail"].get<std::string>().find("started 2 times"), std::string::npos)
      << job.dump();
  expect_problem(last.client().Get("/v1/jobs/" + id + "/net.json"), 422, "interrupted_too_often");
  EXPECT_EQ(completions(last.log()).count(id), 0u);
}

// A wrong password, an unknown database or a server that is not there: papernet says why and
// exits with 1 at once, never hangs, and never prints the password.
TEST_F(MultiNode, AStoreThatCannotBeReachedIsAClearErrorAtStart) {
  struct Case {
    std::string url, says;
  };
  const Case cases[] = {
      {postgres_->login_url(database_, "not-the-password"), "password authentication failed"},
      {postgres_->url("no_such_database"), "does not exist"},
      {"postgresql://postgres:sekrit@127.0.0.1:1/papernet", "Connection refused"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.url);
    std::string output;
    const auto before = std::chrono::steady_clock::now();
    const int code = papernet_serve("--port 0 --store '" + c.url + "'", &output);
    EXPECT_EQ(code, 1) << output;
    EXPECT_NE(output.find(c.says), std::string::npos) << output;
    EXPECT_EQ(output.find("not-the-password"), std::string::npos) << output;
    EXPECT_EQ(output.find("sekrit"), std::string::npos) << output;
    EXPECT_LT(std::chrono::steady_clock::now() - before, 10s);
  }
  std::string output;
  EXPECT_EQ(papernet_serve("--store mysql://localhost/papernet", &output), 2);
  EXPECT_NE(output.find("neither sqlite nor a postgres:// URL"), std::string::npos) << output;
  // The right password works.
  Server s(node({"--workers", "1"}));
  EXPECT_EQ(s.client().Get("/readyz")->status, 200);
}

// PostgreSQL stops under running jobs and comes back: meanwhile the nodes answer
// store_unavailable at once (no hang); then they reconnect, and every job completes once.
TEST(MultiNodeRestart, ThePostgresServerRestartsUnderRunningJobsAndNoJobIsLost) {
  std::string why;
  const auto postgres = PostgresServer::start_private(&why);
  if (!postgres) GTEST_SKIP() << "PostgreSQL is not installed, so this test skips: " << why;
  const std::vector<std::string> flags = {
      "--store", postgres->url(postgres->create_database()), "--lease", "10", "--workers", "1"};
  Server a(flags), b(flags);
  std::vector<std::string> ids;
  for (int i = 0; i < 8; ++i)
    ids.push_back(i < 2 ? submit(a, test_mesh("Duck.glb"), "model/gltf-binary",
                                 "?detail=full&strategy=TU&tab_room_budget=0&colour=none&"
                                 "layout=tile&seed=" +
                                     std::to_string(i + 1))
                        : submit(i % 2 ? a : b, tetra(i), "model/obj", "?strategy=TU"));
  ASSERT_TRUE(wait_until(
      [&] {
        return body(a.client().Get("/v1/jobs/" + ids[0]))["status"] == "running" &&
               body(a.client().Get("/v1/jobs/" + ids[1]))["status"] == "running";
      },
      30s));

  postgres->stop();
  const auto before = std::chrono::steady_clock::now();
  expect_problem(a.client().Get("/readyz"), 503, "store_unavailable");
  expect_problem(b.client().Get("/v1/jobs/" + ids[0]), 503, "store_unavailable");
  EXPECT_LT(std::chrono::steady_clock::now() - before, 5s) << "answers while the store is down";
  EXPECT_EQ(a.client().Get("/healthz")->status, 200);
  EXPECT_NE(a.client().Get("/metrics")->body.find("papernet_store_up 0"), std::string::npos);
  std::this_thread::sleep_for(1500ms);
  postgres->start();

  for (const std::string& id : ids) {
    const json job = wait_final(b, id, 120);
    EXPECT_EQ(job["status"], "succeeded") << job.dump();
  }
  await_logged(ids, [&] { return a.log() + b.log(); });
  const auto on_a = completions(a.log()), on_b = completions(b.log());
  for (const std::string& id : ids)
    EXPECT_EQ((on_a.count(id) ? on_a.at(id) : 0) + (on_b.count(id) ? on_b.at(id) : 0), 1) << id;
  for (const Server* node : {&a, &b}) {
    EXPECT_EQ(node->client().Get("/readyz")->status, 200);
    EXPECT_GE(metric(*node, "papernet_store_reconnects_total"), 1) << node->log();
  }
}

// A statement that times out (here: storing results, slowed by a trigger, under a 1 s
// statement_timeout) fails the job with the database's reason; the node stays up and serves.
TEST_F(MultiNode, AStatementTimeoutFailsTheJobWithItsReasonAndTheNodeStaysUp) {
  Server s({"--store", postgres_->url(database_) + "&options=-c%20statement_timeout%3D1000",
            "--workers", "1", "--reuse-results", "false"});
  postgres_->query(database_,
                   "CREATE FUNCTION slow_down() RETURNS trigger LANGUAGE plpgsql AS "
                   "$$ BEGIN PERFORM pg_sleep(3); RETURN NEW; END $$");
  postgres_->query(database_,
                   "CREATE TRIGGER slow_results BEFORE INSERT ON results FOR EACH ROW "
                   "EXECUTE FUNCTION slow_down()");
  const json failed = wait_final(s, submit(s, tetra(1), "model/obj", "?strategy=TU"));
  EXPECT_EQ(failed["status"], "failed");
  EXPECT_EQ(failed["error"]["code"], "store_failed") << failed.dump();
  EXPECT_NE(failed["error"]["detail"].get<std::string>().find("statement timeout"),
            std::string::npos)
      << failed.dump();
  expect_problem(s.client().Get("/v1/jobs/" + failed["id"].get<std::string>() + "/net.json"), 500,
                 "store_failed");
  postgres_->query(database_, "DROP TRIGGER slow_results ON results");
  EXPECT_EQ(wait_final(s, submit(s, tetra(2), "model/obj", "?strategy=TU"))["status"], "succeeded");
}
