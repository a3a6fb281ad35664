// API keys and tenants over a real socket (README "API keys and tenants", docs/security.md):
// a real `papernet serve --api-keys FILE` against both stores.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

#include "server/api_keys.h"
#include "tests/support/files.h"
#include "tests/support/paths.h"
#include "tests/support/postgres.h"
#include "tests/support/serve_http.h"
#include "tests/support/serve_process.h"

using namespace papernet::test;

class ServeTenants : public BothStores {};
INSTANTIATE_BOTH_STORES(ServeTenants);

namespace {

// SHA-256 of "key-a", "key-b", "key-c" (printf '%s' key-a | sha256sum).
constexpr const char* kHashA = "f10f781241e2246678b6b45c857069208152a53863e47fac33f607ab405006f4";
constexpr const char* kHashB = "a30534a53b23547377ddccbd1ac85a8a84c13db43493c16e55a6abc7b0eba634";
constexpr const char* kHashC = "49043acf9056472a214242c2d15f3087c2d024b0d39ee858c60712b2354f3926";

constexpr const char* kTetraObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

httplib::Headers bearer(const std::string& key) { return {{"Authorization", "Bearer " + key}}; }

// A key file of its own beside the test's data.
fs::path write_keys(const std::string& text) {
  static int counter = 0;
  const fs::path path = fs::temp_directory_path() / ("papernet_keys_" + std::to_string(::getpid()) +
                                                     "_" + std::to_string(counter++) + ".txt");
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string submit_as(const Server& s, const std::string& key, const std::string& mesh,
                      const std::string& query = "?strategy=TU") {
  auto res = s.client().Post("/v1/jobs" + query, bearer(key), mesh, "model/obj");
  EXPECT_TRUE(res);
  if (!res) return "";
  EXPECT_EQ(res->status, 202) << res->body;
  return body(res)["id"];
}

json final_as(const Server& s, const std::string& key, const std::string& id) {
  for (;;) {
    auto res = s.client().Get("/v1/jobs/" + id, bearer(key));
    if (!res || res->status != 200) {
      ADD_FAILURE() << "job " << id << " cannot be read";
      return {};
    }
    const json job = body(res);
    if (job["status"] != "queued" && job["status"] != "running") return job;
    std::this_thread::sleep_for(10ms);
  }
}

// A problem body with `id` written as `as`: two answers that differ only by the id asked for.
std::string with_id(std::string text, const std::string& id, const std::string& as) {
  for (auto at = text.find(id); at != std::string::npos; at = text.find(id, at + as.size()))
    text.replace(at, id.size(), as);
  return text;
}

}  // namespace

TEST_P(ServeTenants, EachTenantSeesListsAndCancelsOnlyItsOwnJobs) {
  const fs::path keys = write_keys(std::string("# shop A\nshop-a ") + kHashA +
                                   " name=front\n\nshop-b " + kHashB + "  # shop B\n");
  Server s({"--workers", "1", "--api-keys", keys.string()});
  auto c = s.client();
  EXPECT_NE(s.log().find("api keys: 2 keys"), std::string::npos) << s.log();

  // Without a key, with a malformed, unknown or over-long one: 401, problem+json.
  auto none = c.Get("/v1/jobs");
  expect_problem(none, 401, "missing_api_key");
  EXPECT_EQ(none->get_header_value("WWW-Authenticate"), "Bearer realm=\"papernet\"");
  expect_problem(c.Post("/v1/jobs", kTetraObj, "model/obj"), 401, "missing_api_key");
  expect_problem(c.Get("/v1/jobs", {{"Authorization", "Basic a2V5LWE6"}}), 401, "invalid_api_key");
  expect_problem(c.Get("/v1/jobs", {{"Authorization", "Bearer"}}), 401, "invalid_api_key");
  expect_problem(c.Get("/v1/jobs", bearer("key-a key-b")), 401, "invalid_api_key");
  expect_problem(c.Get("/v1/jobs", bearer("key-c")), 401, "invalid_api_key");
  expect_problem(c.Get("/v1/jobs", bearer(kHashA)), 401, "invalid_api_key");  // the hash is no key
  auto long_key = c.Get("/v1/jobs", bearer(std::string(1000, 'k')));
  expect_problem(long_key, 401, "invalid_api_key");
  EXPECT_NE(long_key->body.find("longer than 256 bytes"), std::string::npos);
  // Past cpp-httplib's header line limit: 431 naming the line, not a bare 400.
  auto huge = c.Get("/v1/jobs", bearer(std::string(20000, 'k')));
  expect_problem(huge, 431, "request_head_too_large");
  EXPECT_NE(huge->body.find("header line is longer than 8192 bytes"), std::string::npos);
  // Health, readiness and the API description stay open.
  EXPECT_EQ(c.Get("/healthz")->status, 200);
  EXPECT_EQ(c.Get("/readyz")->status, 200);
  EXPECT_EQ(c.Get("/v1/openapi.json")->status, 200);

  const std::string a_job = submit_as(s, "key-a", kTetraObj);
  const json a_final = final_as(s, "key-a", a_job);
  ASSERT_EQ(a_final["status"], "succeeded") << a_final.dump();
  EXPECT_EQ(c.Get("/v1/jobs/" + a_job + "/net.json", bearer("key-a"))->status, 200);
  // Its sheets too, with its key only (the demo and the JS client fetch them one by one).
  EXPECT_EQ(c.Get("/v1/jobs/" + a_job + "/pages/1", bearer("key-a"))->status, 200);
  expect_problem(c.Get("/v1/jobs/" + a_job + "/pages/1"), 401, "missing_api_key");
  expect_problem(c.Get("/v1/jobs/" + a_job + "/textures/0"), 401, "missing_api_key");

  // Tenant B: A's job is not there, exactly as a job that never existed.
  const std::string nobody = "0123456789abcdef0123456789abcdef";
  for (const char* suffix :
       {"", "/net.json", "/net.svg", "/mesh.glb", "/events", "/pages/1", "/textures/0"}) {
    SCOPED_TRACE(suffix);
    auto other = c.Get("/v1/jobs/" + a_job + suffix, bearer("key-b"));
    auto missing = c.Get("/v1/jobs/" + nobody + suffix, bearer("key-b"));
    expect_problem(other, 404, "job_not_found");
    expect_problem(missing, 404, "job_not_found");
    EXPECT_EQ(with_id(other->body, a_job, nobody), missing->body);
  }
  auto cancel_other = c.Delete("/v1/jobs/" + a_job, bearer("key-b"));
  expect_problem(cancel_other, 404, "job_not_found");
  EXPECT_EQ(with_id(cancel_other->body, a_job, nobody),
            c.Delete("/v1/jobs/" + nobody, bearer("key-b"))->body);
  expect_problem(c.Delete("/v1/jobs/" + a_job, bearer("key-a")), 409, "job_finished");

  EXPECT_EQ(body(c.Get("/v1/jobs", bearer("key-b")))["jobs"].size(), 0u);
  const json a_list = body(c.Get("/v1/jobs", bearer("key-a")));
  ASSERT_EQ(a_list["jobs"].size(), 1u);
  EXPECT_EQ(a_list["jobs"][0]["id"], a_job);

  // Result reuse stays within a tenant: B's identical job runs; A's is answered from A's.
  const std::string b_job = submit_as(s, "key-b", kTetraObj);
  const json b_final = final_as(s, "key-b", b_job);
  ASSERT_EQ(b_final["status"], "succeeded") << b_final.dump();
  EXPECT_FALSE(b_final["result"]["metrics"].contains("reused_from")) << b_final.dump();
  auto again = c.Post("/v1/jobs?strategy=TU", bearer("key-a"), kTetraObj, "model/obj");
  ASSERT_EQ(again->status, 202) << again->body;
  EXPECT_EQ(body(again)["result"]["metrics"]["reused_from"], a_job);
  // B cancels its own queued-or-finished job as usual, and lists only its own.
  const json b_list = body(c.Get("/v1/jobs", bearer("key-b")));
  ASSERT_EQ(b_list["jobs"].size(), 1u);
  EXPECT_EQ(b_list["jobs"][0]["id"], b_job);
  fs::remove(keys);
}

TEST_P(ServeTenants, KeysAreReadAgainOnSighupAndWhenTheFileChanges) {
  const fs::path keys = write_keys(std::string("shop-a ") + kHashA + "\n");
  Server s({"--workers", "1", "--api-keys", keys.string()});
  auto c = s.client();
  EXPECT_EQ(c.Get("/v1/jobs", bearer("key-a"))->status, 200);
  expect_problem(c.Get("/v1/jobs", bearer("key-b")), 401, "invalid_api_key");

  // SIGHUP: the file's size and time are kept as they were, so only the signal reloads it.
  const auto written = fs::last_write_time(keys);
  std::ofstream(keys, std::ios::binary | std::ios::trunc) << "shop-b " << kHashB << "\n";
  fs::last_write_time(keys, written);
  s.signal(SIGHUP);
  while (c.Get("/v1/jobs", bearer("key-b"))->status == 401) std::this_thread::sleep_for(20ms);
  expect_problem(c.Get("/v1/jobs", bearer("key-a")), 401, "invalid_api_key");  // revoked

  // A changed file is read again without a signal.
  std::ofstream(keys, std::ios::binary | std::ios::trunc)
      << "shop-b " << kHashB << "\nshop-c " << kHashC << " rate=5\n";
  while (c.Get("/v1/jobs", bearer("key-c"))->status == 401) std::this_thread::sleep_for(50ms);
  EXPECT_EQ(c.Get("/v1/jobs", bearer("key-b"))->status, 200);

  // A file that turns bad keeps the keys read before, and the log says why.
  std::ofstream(keys, std::ios::binary | std::ios::trunc) << "shop-b not-a-hash\n";
  s.signal(SIGHUP);
  while (s.log().find("api keys: not reloaded") == std::string::npos)
    std::this_thread::sleep_for(20ms);
  EXPECT_EQ(c.Get("/v1/jobs", bearer("key-b"))->status, 200);
  EXPECT_NE(s.log().find("is not a SHA-256 in hex"), std::string::npos) << s.log();
  fs::remove(keys);
}

TEST_P(ServeTenants, RateLimitPerKeyIs429WithRetryAfter) {
  // One request per 1000 s: the second is refused however slowly the test runs.
  const fs::path keys =
      write_keys(std::string("shop-a ") + kHashA + " rate=0.001\nshop-b " + kHashB + "\n");
  Server s({"--workers", "1", "--api-keys", keys.string()});
  auto c = s.client();
  EXPECT_EQ(c.Get("/v1/jobs", bearer("key-a"))->status, 200);
  auto limited = c.Get("/v1/jobs", bearer("key-a"));
  expect_problem(limited, 429, "rate_limited");
  EXPECT_GE(std::stoi(limited->get_header_value("Retry-After")), 1);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(c.Get("/v1/jobs", bearer("key-b"))->status, 200);
  fs::remove(keys);
}

TEST_P(ServeTenants, WithoutKeysTheServiceIsOpenAndSaysSo) {
  Server s({"--workers", "1"});
  EXPECT_NE(s.log().find("no --api-keys: the API is open"), std::string::npos) << s.log();
  EXPECT_EQ(s.client().Get("/v1/jobs")->status, 200);
  // A bad key file stops the start, naming the line.
  const fs::path keys = write_keys("shop-a 1234\n");
  const std::string cmd = papernet::test::papernet_binary() + " serve --port 0 --api-keys " +
                          keys.string() + " > " + (s.data() / "bad.txt").string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << status;
  EXPECT_NE(read_file(s.data() / "bad.txt").find(":1: '1234' is not a SHA-256"), std::string::npos)
      << read_file(s.data() / "bad.txt");
  fs::remove(keys);
}

TEST(ServeTenantsKeyFile, TheFormat) {
  using papernet::server::ApiKeyFileError;
  using papernet::server::parse_api_keys;
  EXPECT_EQ(papernet::server::sha256_hex("key-a"), kHashA);
  const auto keys =
      parse_api_keys(std::string("a ") + kHashA + " rate=2.5 share=0.5 name=x\n" + "b " +
                         std::string(kHashB).substr(0, 10) + std::string(kHashB).substr(10) + "\n",
                     "keys");
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys.at(kHashA).tenant, "a");
  EXPECT_EQ(keys.at(kHashA).rate, 2.5);
  EXPECT_EQ(keys.at(kHashA).share, 0.5);
  EXPECT_EQ(keys.at(kHashA).name, "x");
  for (const std::string& bad :
       {std::string("a"), std::string("a ") + kHashA + " colour=red",
        std::string("a ") + kHashA + " share=2", std::string("a ") + kHashA + " rate=-1",
        std::string("a ") + kHashA + "\nb " + kHashA, std::string("# only")})
    EXPECT_THROW(parse_api_keys(bad, "keys"), ApiKeyFileError) << bad;
}

// A key's bucket holds max(1, rate) requests and fills again at `rate` a second; the wait is
// rounded up to whole seconds (Retry-After); each key has a bucket of its own.
TEST(ServeTenantsRateLimiter, ABucketOfRateRequestsFilledAtRateASecond) {
  using papernet::server::RateLimiter;
  using std::chrono::milliseconds;
  RateLimiter limiter;
  const RateLimiter::Clock::time_point t0{};
  EXPECT_EQ(limiter.take("a", 2, t0), 0);
  EXPECT_EQ(limiter.take("a", 2, t0), 0);
  EXPECT_EQ(limiter.take("a", 2, t0), 1);  // empty: half a second to the next, said as 1
  EXPECT_EQ(limiter.take("b", 2, t0), 0);  // another key
  EXPECT_EQ(limiter.take("a", 2, t0 + milliseconds(499)), 1);
  EXPECT_EQ(limiter.take("a", 2, t0 + milliseconds(501)), 0);
  // Refilled for an hour: still no more than 2 at once.
  const auto later = t0 + std::chrono::hours(1);
  EXPECT_EQ(limiter.take("a", 2, later), 0);
  EXPECT_EQ(limiter.take("a", 2, later), 0);
  EXPECT_EQ(limiter.take("a", 2, later), 1);
  // Under one a second: a bucket of one, a wait of 1 / rate seconds.
  EXPECT_EQ(limiter.take("c", 0.25, t0), 0);
  EXPECT_EQ(limiter.take("c", 0.25, t0), 4);
  EXPECT_EQ(limiter.take("c", 0.25, t0 + std::chrono::seconds(3)), 1);
  EXPECT_EQ(limiter.take("c", 0.25, t0 + std::chrono::seconds(4)), 0);
  // No limit.
  for (int i = 0; i < 100; ++i) EXPECT_EQ(limiter.take("d", 0, t0), 0);
}

// Idempotency-Key: a retried submit (same key, same mesh and options) answers 200 with the
// first job; the key with another request is 422; each tenant has keys of its own.
TEST_P(ServeTenants, IdempotencyKeyReturnsTheFirstJobPerTenant) {
  const fs::path keys = write_keys(std::string("shop-a ") + kHashA + "\nshop-b " + kHashB + "\n");
  Server s({"--workers", "1", "--api-keys", keys.string()});
  auto c = s.client();
  auto with_key = [](const std::string& key, const std::string& idem) {
    httplib::Headers h = bearer(key);
    h.emplace("Idempotency-Key", idem);
    return h;
  };
  auto first =
      c.Post("/v1/jobs?strategy=TU&seed=2", with_key("key-a", "order-1"), kTetraObj, "model/obj");
  ASSERT_TRUE(first);
  ASSERT_EQ(first->status, 202) << first->body;
  const std::string id = body(first)["id"];
  EXPECT_EQ(first->get_header_value("Location"), "/v1/jobs/" + id);

  // The retry, with the options in another order: the same request, the first job.
  auto retry =
      c.Post("/v1/jobs?seed=2&strategy=TU", with_key("key-a", "order-1"), kTetraObj, "model/obj");
  ASSERT_TRUE(retry);
  EXPECT_EQ(retry->status, 200) << retry->body;
  EXPECT_EQ(body(retry)["id"], id);
  EXPECT_EQ(retry->get_header_value("Location"), "/v1/jobs/" + id);
  EXPECT_EQ(retry->get_header_value("Idempotent-Replayed"), "true");
  // Multipart with its own boundary, same mesh and options: still the same request.
  httplib::MultipartFormDataItems items = {
      {"mesh", kTetraObj, "t.obj", "model/obj"},
      {"options", R"({"strategy":"TU","seed":2})", "", "application/json"}};
  auto multipart = c.Post("/v1/jobs", with_key("key-a", "order-1"), items);
  ASSERT_TRUE(multipart);
  EXPECT_EQ(multipart->status, 200) << multipart->body;
  EXPECT_EQ(body(multipart)["id"], id);

  // The key with another body (another seed, another mesh): 422, and no job made.
  auto other =
      c.Post("/v1/jobs?strategy=TU&seed=3", with_key("key-a", "order-1"), kTetraObj, "model/obj");
  expect_problem(other, 422, "idempotency_key_reused");
  expect_problem(c.Post("/v1/jobs?strategy=TU&seed=2", with_key("key-a", "order-1"),
                        std::string(kTetraObj) + "\n", "model/obj"),
                 422, "idempotency_key_reused");
  EXPECT_EQ(body(c.Get("/v1/jobs", bearer("key-a")))["jobs"].size(), 1u);

  // Another tenant with the same key: a job of its own.
  auto b =
      c.Post("/v1/jobs?strategy=TU&seed=2", with_key("key-b", "order-1"), kTetraObj, "model/obj");
  ASSERT_TRUE(b);
  EXPECT_EQ(b->status, 202) << b->body;
  EXPECT_NE(body(b)["id"], id);
  auto b_retry =
      c.Post("/v1/jobs?strategy=TU&seed=2", with_key("key-b", "order-1"), kTetraObj, "model/obj");
  EXPECT_EQ(body(b_retry)["id"], body(b)["id"]);
  // A new key is a new job; without a key every submit is one.
  auto second =
      c.Post("/v1/jobs?strategy=TU&seed=2", with_key("key-a", "order-2"), kTetraObj, "model/obj");
  EXPECT_EQ(second->status, 202);
  EXPECT_NE(body(second)["id"], id);
  // A key that is no key: 400.
  expect_problem(
      c.Post("/v1/jobs", with_key("key-a", std::string(300, 'x')), kTetraObj, "model/obj"), 400,
      "malformed_request");
  EXPECT_EQ(final_as(s, "key-a", id)["status"], "succeeded");
  // After the job ended, the retry still answers with it (now finished).
  auto late =
      c.Post("/v1/jobs?strategy=TU&seed=2", with_key("key-a", "order-1"), kTetraObj, "model/obj");
  EXPECT_EQ(late->status, 200);
  EXPECT_EQ(body(late)["status"], "succeeded");
  fs::remove(keys);
}

// Many retries of one request at once (a client's retry storm): one job.
TEST_P(ServeTenants, ConcurrentRetriesOfOneKeyMakeOneJob) {
  Server s({"--workers", "1"});
  std::vector<std::string> ids(8);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < ids.size(); ++i)
    threads.emplace_back([&, i] {
      for (;;) {
        auto res = s.client().Post("/v1/jobs?strategy=TU", {{"Idempotency-Key", "storm"}},
                                   kTetraObj, "model/obj");
        if (res && res->status == 409) continue;  // idempotency_key_in_use: retry
        if (res && (res->status == 200 || res->status == 202)) ids[i] = body(res)["id"];
        return;
      }
    });
  for (auto& t : threads) t.join();
  for (const std::string& id : ids) EXPECT_EQ(id, ids[0]);
  EXPECT_EQ(body(s.client().Get("/v1/jobs"))["jobs"].size(), 1u);
}

// share=: a tenant's queued jobs fill at most its part of the queue; others still queue.
TEST_P(ServeTenants, QueueShareCapsATenantsQueuedJobs) {
  const fs::path keys =
      write_keys(std::string("shop-a ") + kHashA + " share=0.25\nshop-b " + kHashB + "\n");
  Server s({"--workers", "1", "--queue-length", "4", "--api-keys", keys.string()});
  auto c = s.client();
  // The one worker is busy with a long job of B's, so what follows stays queued.
  const std::string busy =
      submit_as(s, "key-b", test_mesh("reference.obj"), "?detail=full&strategy=TU&time_limit=60");
  while (body(c.Get("/v1/jobs/" + busy, bearer("key-b")))["status"] == "queued")
    std::this_thread::sleep_for(5ms);
  ASSERT_EQ(body(c.Get("/v1/jobs/" + busy, bearer("key-b")))["status"], "running")
      << "the test needs a job that runs for a while";
  const std::string queued = submit_as(s, "key-a", kTetraObj, "?strategy=TU&seed=1");
  auto over = c.Post("/v1/jobs?strategy=TU&seed=2", bearer("key-a"), kTetraObj, "model/obj");
  expect_problem(over, 429, "queue_full");
  EXPECT_NE(over->body.find("share of the queue (1 of 4 jobs)"), std::string::npos) << over->body;
  EXPECT_FALSE(over->get_header_value("Retry-After").empty());
  // B, without a share, queues as before.
  submit_as(s, "key-b", kTetraObj, "?strategy=TU&seed=3");
  EXPECT_EQ(c.Delete("/v1/jobs/" + busy, bearer("key-b"))->status, 202);
  EXPECT_EQ(final_as(s, "key-a", queued)["status"], "succeeded");
  fs::remove(keys);
}
