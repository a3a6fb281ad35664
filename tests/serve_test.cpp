// End-to-end: starts the real `papernet serve` on a free loopback port and speaks HTTP to it.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

namespace {

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string test_mesh(const std::string& name) {
  return read_file(fs::path(PAPERNET_TEST_DATA) / name);
}

int free_port() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  socklen_t len = sizeof addr;
  getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  close(fd);
  return ntohs(addr.sin_port);
}

// Three triangles on one edge: loads fine, cannot be unfolded (non-manifold edge).
constexpr const char* kNonManifoldObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";

// One `papernet serve` process with its own data directory.
class Server {
 public:
  explicit Server(std::vector<std::string> flags, fs::path data = {})
      : flags_(std::move(flags)),
        data_(data.empty()
                  ? fs::temp_directory_path() / ("papernet_serve_" + std::to_string(::getpid()) +
                                                 "_" + std::to_string(counter_++))
                  : data) {
    fs::create_directories(data_);
    start();
  }
  ~Server() {
    stop(SIGKILL);
    if (owns_) fs::remove_all(data_);
  }

  void start() {
    port_ = free_port();
    std::vector<std::string> args = {
        "papernet", "serve",        "--port",       std::to_string(port_),
        "--data",   data_.string(), "--access-log", "false"};
    args.insert(args.end(), flags_.begin(), flags_.end());
    pid_ = fork();
    if (pid_ == 0) {
      const std::string log = (data_ / "server.log").string();
      freopen(log.c_str(), "a", stderr);
      freopen("/dev/null", "w", stdout);
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(PAPERNET_BINARY, argv.data());
      _exit(127);
    }
    for (int i = 0; i < 200; ++i) {
      if (auto res = client().Get("/healthz"); res && res->status == 200) return;
      std::this_thread::sleep_for(25ms);
    }
    ADD_FAILURE() << "papernet serve did not come up; log:\n" << log();
  }
  /// Sends `sig` and waits for the process; returns its exit status.
  int stop(int sig) {
    if (pid_ <= 0) return -1;
    kill(pid_, sig);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    return status;
  }
  void signal(int sig) { kill(pid_, sig); }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(30, 0);
    return c;
  }
  std::string log() const { return read_file(data_ / "server.log"); }
  const fs::path& data() const { return data_; }
  void keep_data() { owns_ = false; }

 private:
  static inline int counter_ = 0;
  std::vector<std::string> flags_;
  fs::path data_;
  int port_ = 0;
  pid_t pid_ = -1;
  bool owns_ = true;
};

json body(const httplib::Result& res) { return json::parse(res->body); }

std::string submit(const Server& s, const std::string& mesh, const std::string& type,
                   const std::string& query = "") {
  auto res = s.client().Post("/v1/jobs" + query, mesh, type);
  EXPECT_TRUE(res);
  if (!res) return "";
  EXPECT_EQ(res->status, 202) << res->body;
  EXPECT_EQ(res->get_header_value("Location"), "/v1/jobs/" + body(res)["id"].get<std::string>());
  return body(res)["id"];
}

json wait_final(const Server& s, const std::string& id, int seconds = 60) {
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

void expect_problem(const httplib::Result& res, int status, const std::string& code) {
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, status) << res->body;
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/problem+json");
  const json doc = json::parse(res->body, nullptr, false);
  ASSERT_TRUE(doc.is_object()) << res->body;
  EXPECT_EQ(doc["code"], code) << res->body;
  EXPECT_EQ(doc["status"], status);
  EXPECT_FALSE(doc["detail"].get<std::string>().empty());
}

// True when this build unfolds (the job did not fail with pipeline_unavailable).
bool unfolds(const json& job) {
  return !(job["status"] == "failed" && job["error"]["code"] == "pipeline_unavailable");
}

}  // namespace

TEST(ServeTest, HealthReadinessMetricsAndOpenApi) {
  Server s({"--workers", "1"});
  auto c = s.client();
  EXPECT_EQ(c.Get("/healthz")->status, 200);
  EXPECT_EQ(c.Get("/readyz")->status, 200);
  auto metrics = c.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_NE(metrics->body.find("papernet_queue_length 0"), std::string::npos);
  EXPECT_NE(metrics->body.find("papernet_http_requests_total{status=\"200\"}"), std::string::npos);
  auto api = c.Get("/v1/openapi.json");
  ASSERT_TRUE(api);
  const json doc = json::parse(api->body);
  EXPECT_EQ(doc["openapi"].get<std::string>().substr(0, 2), "3.");
  EXPECT_TRUE(doc["paths"].contains("/v1/jobs/{id}"));
}

TEST(ServeTest, SubmitPollAndFetchObj) {
  Server s({"--workers", "1"});
  const std::string id = submit(s, test_mesh("sample.obj"), "model/obj", "?strategy=TU&seed=3");
  const json job = wait_final(s, id);
  EXPECT_EQ(job["options"]["strategy"], "TU");
  EXPECT_EQ(job["input"]["format"], "obj");
  if (!unfolds(job)) GTEST_SKIP() << "needs the unfolder: " << job["error"]["detail"];
  ASSERT_TRUE(job["status"] == "succeeded" || job["status"] == "approximated") << job.dump();
  auto c = s.client();
  auto net = c.Get("/v1/jobs/" + id + "/net.json");
  ASSERT_EQ(net->status, 200);
  const json doc = json::parse(net->body);
  EXPECT_EQ(doc["format"], "papernet.net/1");
  EXPECT_EQ(doc["metrics"]["overlaps"], 0);
  EXPECT_EQ(doc["net"]["faces"].size(), doc["mesh"]["faces"].size());
  auto svg = c.Get("/v1/jobs/" + id + "/net.svg");
  ASSERT_EQ(svg->status, 200);
  EXPECT_NE(svg->body.find("<svg"), std::string::npos);
  auto pdf = c.Get("/v1/jobs/" + id + "/net.pdf");
  ASSERT_EQ(pdf->status, 200);
  EXPECT_EQ(pdf->body.substr(0, 5), "%PDF-");
  auto glb = c.Get("/v1/jobs/" + id + "/mesh.glb");
  ASSERT_EQ(glb->status, 200);
  EXPECT_EQ(glb->body.substr(0, 4), "glTF");
}

TEST(ServeTest, SubmitGlbDracoAndMultipartGltf) {
  Server s({"--workers", "1"});
  std::vector<std::string> ids = {
      submit(s, test_mesh("testplate.glb"), "model/gltf-binary", "?strategy=TU"),
      submit(s, test_mesh("Box_Draco.glb"), "", "?strategy=TU")};
  const fs::path box = fs::path(PAPERNET_SHARED_DATA) / "meshes/gltf/draco__Box";
  if (fs::exists(box / "Box.gltf")) {
    httplib::MultipartFormDataItems items = {
        {"mesh", read_file(box / "Box.gltf"), "Box.gltf", "model/gltf+json"},
        {"buffers", read_file(box / "Box0.bin"), "Box0.bin", "application/octet-stream"},
        {"options", R"({"strategy":"TU","seed":5})", "", "application/json"}};
    auto res = s.client().Post("/v1/jobs", items);
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 202) << res->body;
    EXPECT_EQ(body(res)["input"]["format"], "gltf");
    EXPECT_EQ(body(res)["options"]["seed"], 5);
    ids.push_back(body(res)["id"]);
  }
  for (const std::string& id : ids) {
    const json job = wait_final(s, id);
    // Every upload must load: whatever happens next, never an unreadable mesh.
    EXPECT_NE(job["error"].is_object() ? job["error"]["code"] : json("none"), "unreadable_mesh")
        << job.dump();
    EXPECT_GT(job["input"]["faces"].get<int>(), 0) << job.dump();
    if (unfolds(job)) {
      EXPECT_EQ(job["status"], "succeeded") << job.dump();
      auto net = s.client().Get("/v1/jobs/" + id + "/net.json");
      ASSERT_TRUE(net);
      EXPECT_EQ(json::parse(net->body)["net"]["faces"].size(), job["result"]["faces"]);
    }
  }
  if (!fs::exists(box / "Box.gltf")) GTEST_SKIP() << "needs ../shared/data: " << box;
}

TEST(ServeTest, EventStreamEndsWithTheFinalState) {
  Server s({"--workers", "1"});
  const std::string id = submit(s, test_mesh("sample.obj"), "model/obj", "?strategy=TU");
  std::string stream;
  auto res = s.client().Get("/v1/jobs/" + id + "/events", [&](const char* data, size_t n) {
    stream.append(data, n);
    return true;
  });
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(res->get_header_value("Content-Type"), "text/event-stream");
  const auto done = stream.rfind("event: done\ndata: ");
  ASSERT_NE(done, std::string::npos) << stream;
  const std::string data = stream.substr(done + 18, stream.find('\n', done + 18) - done - 18);
  const json last = json::parse(data);
  EXPECT_EQ(last["id"], id);
  EXPECT_EQ(last, wait_final(s, id)) << "the last event is the job's final state";
  if (!unfolds(last)) GTEST_SKIP() << "needs the unfolder for progress events";
  EXPECT_NE(stream.find("event: progress"), std::string::npos) << stream;
  EXPECT_NE(stream.find("\"phase\":\"unfold\""), std::string::npos)
      << "the stream shows the unfolder's progress";
}

TEST(ServeTest, EveryErrorCodeFromTheInputThatCausesIt) {
  Server s({"--workers", "1", "--max-body-bytes", "100000", "--max-faces", "500"});
  auto c = s.client();
  const std::string obj = test_mesh("sample.obj");  // 1000 faces, 81 KB
  expect_problem(c.Post("/v1/jobs?strategy=FAST", obj, "model/obj"), 400, "invalid_option_value");
  expect_problem(c.Post("/v1/jobs?colour=red", obj, "model/obj"), 400, "unknown_option");
  expect_problem(c.Post("/v1/jobs?time_limit=100000", obj, "model/obj"), 400,
                 "option_out_of_range");
  expect_problem(c.Get("/v1/jobs/0123456789abcdef0123456789abcdef"), 404, "job_not_found");
  expect_problem(c.Get("/v1/jobs/not-a-job-id"), 404, "job_not_found");
  expect_problem(c.Get("/v1/jobs/..%2F..%2Fetc%2Fpasswd/net.json"), 404, "not_found");
  expect_problem(c.Get("/v1/nothing"), 404, "not_found");
  expect_problem(c.Post("/v1/jobs", std::string(150000, 'v'), "model/obj"), 413,
                 "payload_too_large");
  expect_problem(c.Post("/v1/jobs", "\x89PNG\r\n", "image/png"), 415, "unsupported_format");
  expect_problem(c.Post("/v1/jobs", "hello\nworld\n", "application/octet-stream"), 415,
                 "unsupported_format");

  // Faults found by a worker fail the job; its result answers with the problem.
  const std::string too_big = submit(s, obj, "model/obj");
  EXPECT_EQ(wait_final(s, too_big)["error"]["code"], "too_many_faces");
  expect_problem(c.Get("/v1/jobs/" + too_big + "/net.json"), 413, "too_many_faces");

  const std::string bad = submit(s, kNonManifoldObj, "model/obj");
  const json failed = wait_final(s, bad);
  EXPECT_EQ(failed["status"], "failed");
  EXPECT_EQ(failed["error"]["code"], "invalid_mesh");
  EXPECT_FALSE(failed["error"]["reasons"].empty()) << failed.dump();
  expect_problem(c.Get("/v1/jobs/" + bad + "/net.svg"), 422, "invalid_mesh");
  expect_problem(c.Delete("/v1/jobs/" + bad), 409, "job_finished");
}

TEST(ServeTest, ListsRecentJobsPaged) {
  Server s({"--workers", "1"});
  std::vector<std::string> ids;
  for (int i = 0; i < 3; ++i)
    ids.push_back(submit(s, kNonManifoldObj + std::string(i, '\n'), "model/obj"));
  auto page = body(s.client().Get("/v1/jobs?limit=2"));
  ASSERT_EQ(page["jobs"].size(), 2u);
  EXPECT_EQ(page["jobs"][0]["id"], ids[2]);
  EXPECT_EQ(page["jobs"][1]["id"], ids[1]);
  ASSERT_TRUE(page["next"].is_string());
  auto next = body(s.client().Get(page["next"].get<std::string>()));
  ASSERT_EQ(next["jobs"].size(), 1u);
  EXPECT_EQ(next["jobs"][0]["id"], ids[0]);
  expect_problem(s.client().Get("/v1/jobs?limit=0"), 400, "malformed_request");
}

// Needs jobs that take a while: a full queue, cancelling a running job, a graceful stop.
TEST(ServeTest, QueueFullCancelAndShutdown) {
  Server s({"--workers", "1", "--queue-length", "1", "--shutdown-grace", "30"});
  const std::string mesh = test_mesh("reference.obj");
  const std::string first = submit(s, mesh, "model/obj", "?strategy=TU&time_limit=60");
  std::this_thread::sleep_for(300ms);
  const json probe = body(s.client().Get("/v1/jobs/" + first));
  if (!unfolds(probe)) GTEST_SKIP() << "needs the unfolder: " << probe["error"]["detail"];
  if (probe["status"] != "running") GTEST_SKIP() << "job finished too fast to test with";
  const std::string queued = submit(s, mesh, "model/obj", "?strategy=TU&seed=2");
  auto full = s.client().Post("/v1/jobs?seed=3", mesh, "model/obj");
  expect_problem(full, 429, "queue_full");
  EXPECT_FALSE(full->get_header_value("Retry-After").empty());
  EXPECT_EQ(body(s.client().Get("/v1/jobs/" + queued))["progress"]["queue_position"], 1);

  EXPECT_EQ(s.client().Delete("/v1/jobs/" + queued)->status, 202);
  EXPECT_EQ(wait_final(s, queued)["status"], "cancelled");
  const auto before = std::chrono::steady_clock::now();
  EXPECT_EQ(s.client().Delete("/v1/jobs/" + first)->status, 202);
  EXPECT_EQ(wait_final(s, first)["status"], "cancelled");
  EXPECT_LT(std::chrono::steady_clock::now() - before, 1500ms);
  expect_problem(s.client().Get("/v1/jobs/" + first + "/net.json"), 410, "job_cancelled");

  // Graceful stop: while the running job has its grace period, no new work is accepted.
  const std::string running = submit(s, mesh, "model/obj", "?strategy=TU&seed=4");
  std::this_thread::sleep_for(300ms);
  s.signal(SIGTERM);
  std::this_thread::sleep_for(200ms);
  expect_problem(s.client().Post("/v1/jobs", mesh, "model/obj"), 503, "shutting_down");
  expect_problem(s.client().Get("/readyz"), 503, "shutting_down");
}

// kill -9 with jobs queued and running; a restart finishes every one and loses no result.
TEST(ServeTest, KillNineThenRestartFinishesEveryJob) {
  auto server = std::make_unique<Server>(std::vector<std::string>{"--workers", "1"});
  const fs::path data = server->data();
  const std::string finished = submit(*server, test_mesh("mirror.ply"), "", "?strategy=TU");
  const json done_before = wait_final(*server, finished);
  if (!unfolds(done_before)) GTEST_SKIP() << "needs the unfolder";
  ASSERT_EQ(done_before["status"], "succeeded") << done_before.dump();
  const std::string net_before = server->client().Get("/v1/jobs/" + finished + "/net.json")->body;

  std::vector<std::string> ids = {finished};
  for (const char* name : {"sample.obj", "testplate.glb", "Box_Draco.glb"})
    ids.push_back(submit(*server, test_mesh(name), "", "?strategy=TU"));
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(body(server->client().Get("/v1/jobs/" + ids[1]))["status"], "running");
  EXPECT_EQ(body(server->client().Get("/v1/jobs/" + ids[3]))["status"], "queued");
  server->keep_data();
  EXPECT_TRUE(WIFSIGNALED(server->stop(SIGKILL)));
  server.reset();

  Server restarted({"--workers", "1"}, data);
  for (const std::string& id : ids) {
    const json job = wait_final(restarted, id);
    EXPECT_EQ(job["status"], "succeeded") << job.dump();
    auto net = restarted.client().Get("/v1/jobs/" + id + "/net.json");
    ASSERT_TRUE(net);
    EXPECT_EQ(net->status, 200);
  }
  EXPECT_EQ(body(restarted.client().Get("/v1/jobs/" + ids[1]))["result"]["metrics"]["faces"], 1000);
  EXPECT_EQ(restarted.client().Get("/v1/jobs/" + finished + "/net.json")->body, net_before);
}
