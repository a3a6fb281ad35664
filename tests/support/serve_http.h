// The HTTP helpers the end-to-end tests share: a response's JSON, a job submitted to a `Server`
// (serve_process.h) and polled until it runs, reaches a phase or ends, and a problem response
// checked.
#pragma once

#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "tests/support/sanitized.h"
#include "tests/support/serve_process.h"

namespace papernet::test {

using nlohmann::json;
using namespace std::chrono_literals;

inline json body(const httplib::Result& res) { return json::parse(res->body); }

inline std::string submit(const Server& s, const std::string& mesh, const std::string& type,
                          const std::string& query = "") {
  auto res = s.client().Post("/v1/jobs" + query, mesh, type);
  EXPECT_TRUE(res);
  if (!res) return "";
  EXPECT_EQ(res->status, 202) << res->body;
  EXPECT_EQ(res->get_header_value("Location"), "/v1/jobs/" + body(res)["id"].get<std::string>());
  return body(res)["id"];
}

inline json wait_final(const Server& s, const std::string& id, int seconds = 60) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  json job;
  while (std::chrono::steady_clock::now() < end) {
    auto res = s.client().Get("/v1/jobs/" + id);
    if (res && res->status == 200) {
      job = body(res);
      const std::string st = job["status"];
      if (st != "queued" && st != "running") return job;
    }
    std::this_thread::sleep_for(20ms);
  }
  ADD_FAILURE() << "job " << id << " did not finish: " << job.dump();
  return job;
}

// Polls until the job runs; tests that interrupt a running job need it caught in the act.
inline void wait_running(const Server& s, const std::string& id) {
  const auto end = std::chrono::steady_clock::now() + 30s;
  std::string st;
  while (std::chrono::steady_clock::now() < end) {
    st = body(s.client().Get("/v1/jobs/" + id))["status"];
    if (st != "queued") break;
    std::this_thread::sleep_for(5ms);
  }
  ASSERT_EQ(st, "running") << "the test needs a job that runs for a while";
}

// Polls until the running job reports `phase` (its progress), or it ends. The wait (60 s, 240 s
// sanitized) is a bound on a slow machine, not a figure (docs/reliability.md, "Sanitizers").
inline void wait_phase(const Server& s, const std::string& id, const std::string& phase) {
#ifdef PAPERNET_TEST_SANITIZED
  const auto end = std::chrono::steady_clock::now() + 240s;
#else
  const auto end = std::chrono::steady_clock::now() + 60s;
#endif
  json job;
  while (std::chrono::steady_clock::now() < end) {
    job = body(s.client().Get("/v1/jobs/" + id));
    if (job["status"] != "queued" && job["status"] != "running") break;
    if (job["progress"].value("phase", "") == phase) return;
    std::this_thread::sleep_for(5ms);
  }
  FAIL() << "the test needs a job caught in its " << phase << " phase: " << job.dump();
}

inline void expect_problem(const httplib::Result& res, int status, const std::string& code) {
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, status) << res->body;
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/problem+json");
  const json doc = json::parse(res->body, nullptr, false);
  ASSERT_TRUE(doc.is_object()) << res->body;
  EXPECT_EQ(doc["code"], code) << res->body;
  EXPECT_EQ(doc["status"], status);
  EXPECT_FALSE(doc["detail"].get<std::string>().empty());
}

}  // namespace papernet::test
