// /metrics over a real socket: latency histograms per route (event streams apart), failures by
// status and problem code, open event streams, queued jobs per tenant; against both stores.
#include <gtest/gtest.h>

#include <atomic>
#include <fstream>

#include "server/metrics.h"
#include "tests/support/files.h"
#include "tests/support/postgres.h"
#include "tests/support/serve_http.h"
#include "tests/support/serve_process.h"

using namespace papernet::test;

class ServeMetrics : public BothStores {};
INSTANTIATE_BOTH_STORES(ServeMetrics);

namespace {

constexpr const char* kTetraObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

// The value of the sample `series` (name and labels, exactly as exposed); -1 when absent.
double sample(const std::string& text, const std::string& series) {
  const std::string line = "\n" + series + " ";
  const auto at = text.find(line);
  if (at == std::string::npos) return -1;
  return std::stod(text.substr(at + line.size()));
}

}  // namespace

TEST_P(ServeMetrics, RoutesFailuresStreamsAndTenantQueues) {
  // SHA-256 of "key-a" and "key-b" (tenants_test.cpp).
  const fs::path keys =
      fs::temp_directory_path() / ("papernet_metrics_keys_" + std::to_string(::getpid()) + ".txt");
  std::ofstream(keys)
      << "shop-a f10f781241e2246678b6b45c857069208152a53863e47fac33f607ab405006f4\n"
         "shop-b a30534a53b23547377ddccbd1ac85a8a84c13db43493c16e55a6abc7b0eba634\n";
  Server s({"--workers", "1", "--api-keys", keys.string()});
  auto c = s.client();
  const httplib::Headers a = {{"Authorization", "Bearer key-a"}};
  const httplib::Headers b = {{"Authorization", "Bearer key-b"}};

  // B's long job keeps the one worker busy, so that A's jobs stay queued.
  auto busy = c.Post("/v1/jobs?detail=full&strategy=TU&time_limit=60", b,
                     test_mesh("reference.obj"), "model/obj");
  ASSERT_EQ(busy->status, 202) << busy->body;
  const std::string busy_id = body(busy)["id"];
  while (body(c.Get("/v1/jobs/" + busy_id, b))["status"] == "queued")
    std::this_thread::sleep_for(5ms);
  for (int seed = 1; seed <= 2; ++seed)
    ASSERT_EQ(c.Post("/v1/jobs?strategy=TU&seed=" + std::to_string(seed), a, kTetraObj, "model/obj")
                  ->status,
              202);
  // Failures of several kinds.
  EXPECT_EQ(c.Get("/v1/jobs")->status, 401);
  EXPECT_EQ(c.Get("/v1/jobs/0123456789abcdef0123456789abcdef", a)->status, 404);
  EXPECT_EQ(c.Post("/v1/jobs?strategy=XX", a, kTetraObj, "model/obj")->status, 400);
  EXPECT_EQ(c.Get("/nowhere")->status, 404);

  // An event stream held open while /metrics is read.
  std::atomic<bool> opened{false}, done{false};
  std::thread stream([&] {
    auto sc = s.client();
    sc.Get("/v1/jobs/" + busy_id + "/events", b, [&](const char*, size_t) {
      opened = true;
      return !done.load();
    });
  });
  while (!opened) std::this_thread::sleep_for(5ms);
  const std::string open = c.Get("/metrics")->body;
  EXPECT_EQ(sample(open, "papernet_http_open_streams"), 1) << open;
  EXPECT_EQ(sample(open, "papernet_tenant_queue_length{tenant=\"shop-a\"}"), 2) << open;
  EXPECT_EQ(sample(open, "papernet_tenant_queue_length{tenant=\"shop-b\"}"), -1) << open;
  EXPECT_GE(sample(open, "papernet_http_request_duration_seconds_count{route=\"POST /v1/jobs\"}"),
            3)
      << open;
  EXPECT_GE(
      sample(open, "papernet_http_request_duration_seconds_count{route=\"GET /v1/jobs/{id}\"}"), 1);
  EXPECT_EQ(sample(open,
                   "papernet_http_request_duration_seconds_bucket{route=\"POST "
                   "/v1/jobs\",le=\"+Inf\"}"),
            sample(open, "papernet_http_request_duration_seconds_count{route=\"POST /v1/jobs\"}"));
  EXPECT_EQ(sample(open, "papernet_http_failures_total{status=\"401\",code=\"missing_api_key\"}"),
            1)
      << open;
  EXPECT_EQ(sample(open, "papernet_http_failures_total{status=\"404\",code=\"job_not_found\"}"), 1);
  EXPECT_EQ(
      sample(open, "papernet_http_failures_total{status=\"400\",code=\"invalid_option_value\"}"),
      1);
  EXPECT_EQ(sample(open, "papernet_http_failures_total{status=\"404\",code=\"not_found\"}"), 1);
  EXPECT_EQ(sample(open, "papernet_http_stream_duration_seconds_count"), 0);
  // The stream is in no route's histogram: it would swamp the latencies.
  EXPECT_EQ(open.find("route=\"GET /v1/jobs/{id}/events\""), std::string::npos);

  done = true;
  EXPECT_EQ(c.Delete("/v1/jobs/" + busy_id, b)->status, 202);  // ends the stream too
  stream.join();
  std::string after;
  for (int i = 0; i < 200; ++i) {
    after = c.Get("/metrics")->body;
    if (sample(after, "papernet_http_stream_duration_seconds_count") == 1) break;
    std::this_thread::sleep_for(10ms);
  }
  EXPECT_EQ(sample(after, "papernet_http_stream_duration_seconds_count"), 1) << after;
  EXPECT_EQ(sample(after, "papernet_http_open_streams"), 0);
  fs::remove(keys);
}

TEST(MetricsRoutes, LabelsStayFew) {
  using papernet::server::route_of;
  EXPECT_EQ(route_of("GET", "/v1/jobs/0123456789abcdef0123456789abcdef"), "GET /v1/jobs/{id}");
  EXPECT_EQ(route_of("GET", "/v1/jobs/x/net.svg"), "GET /v1/jobs/{id}/{file}");
  EXPECT_EQ(route_of("GET", "/v1/jobs/x/events"), "GET /v1/jobs/{id}/events");
  EXPECT_EQ(route_of("GET", "/v1/jobs/x/pages/12"), "GET /v1/jobs/{id}/pages/{k}");
  EXPECT_EQ(route_of("GET", "/v1/jobs/x/textures/0"), "GET /v1/jobs/{id}/textures/{k}");
  EXPECT_EQ(route_of("GET", "/v1/jobs/x/pages/"), "GET other");
  EXPECT_EQ(route_of("GET", "/v1/jobs/x/pages/1x"), "GET other");
  EXPECT_EQ(route_of("GET", "/v1/jobs/x/secret.txt"), "GET other");
  EXPECT_EQ(route_of("POST", "/v1/jobs"), "POST /v1/jobs");
  EXPECT_EQ(route_of("BREW", "/healthz"), "OTHER /healthz");
  EXPECT_EQ(route_of("GET", "/index.html"), "GET other");
}
