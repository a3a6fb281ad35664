// Webhooks over real sockets (docs/security.md "Webhooks"): a real `papernet serve` calling a
// real receiver, a cpp-httplib server on loopback in this test, against both stores. The
// receiver checks the signature with the documented algorithm, computed here with OpenSSL.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <sys/socket.h>

#include <deque>
#include <mutex>

#include "server/webhooks.h"
#include "tests/support/postgres.h"
#include "tests/support/serve_http.h"
#include "tests/support/serve_process.h"

using namespace papernet::test;

class ServeWebhooks : public BothStores {};
INSTANTIATE_BOTH_STORES(ServeWebhooks);

namespace {

constexpr const char* kTetraObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
constexpr const char* kSecret = "whsec-test-secret";

// One callback as the receiver got it.
struct Call {
  std::string signature;
  std::string body;
  std::string job;
};

// A webhook receiver on 127.0.0.1: answers the statuses queued in `answers`, then `then`.
class Receiver {
 public:
  Receiver() {
    http_.Post("/hook", [this](const httplib::Request& req, httplib::Response& res) {
      std::lock_guard lock(mutex_);
      calls_.push_back({req.get_header_value("X-Papernet-Signature"), req.body,
                        req.get_header_value("X-Papernet-Job")});
      res.status = then_;
      if (!answers_.empty()) {
        res.status = answers_.front();
        answers_.pop_front();
      }
      if (res.status == 302)
        res.set_header("Location", "http://127.0.0.1:" + std::to_string(port_) + "/elsewhere");
      res.set_content("thanks", "text/plain");
    });
    http_.Post("/elsewhere", [this](const httplib::Request&, httplib::Response& res) {
      std::lock_guard lock(mutex_);
      ++redirected_;
      res.set_content("no", "text/plain");
    });
    port_ = http_.bind_to_any_port("127.0.0.1");
    thread_ = std::thread([this] { http_.listen_after_bind(); });
  }
  ~Receiver() {
    http_.stop();
    thread_.join();
  }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/hook"; }
  void answer(std::deque<int> first, int then) {
    std::lock_guard lock(mutex_);
    answers_ = std::move(first);
    then_ = then;
  }
  std::vector<Call> calls() {
    std::lock_guard lock(mutex_);
    return calls_;
  }
  int redirected() {
    std::lock_guard lock(mutex_);
    return redirected_;
  }
  // Waits until `n` calls came (or `seconds` passed); returns the calls.
  std::vector<Call> wait_for(std::size_t n, int seconds = 20) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    while (calls().size() < n && std::chrono::steady_clock::now() < end)
      std::this_thread::sleep_for(20ms);
    return calls();
  }

 private:
  httplib::Server http_;
  std::thread thread_;
  int port_ = 0;
  std::mutex mutex_;
  std::vector<Call> calls_;
  std::deque<int> answers_;
  int then_ = 200;
  int redirected_ = 0;
};

// A host that takes connections (the kernel's backlog) and never answers.
class Silent {
 public:
  Silent() {
    fd_ = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    EXPECT_EQ(listen(fd_, 64), 0);
    socklen_t len = sizeof a;
    getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
  }
  ~Silent() { close(fd_); }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/hook"; }

 private:
  int fd_ = -1;
  int port_ = 0;
};

std::string encode(const std::string& text) {
  std::string out;
  for (const unsigned char c : text) {
    if (std::isalnum(c) || c == '.' || c == '-' || c == '_') {
      out += static_cast<char>(c);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    }
  }
  return out;
}

std::string with_callback(const std::string& url) {
  std::string query = "?strategy=TU&callback_url=";
  query += encode(url);
  return query;
}

// The documented check, done independently of the server's code: HMAC-SHA256 of "<t>.<body>"
// under the secret, in lower-case hex, compared with v1; t within five minutes of now.
bool signature_valid(const std::string& header, const std::string& body,
                     const std::string& secret) {
  const auto comma = header.find(",v1=");
  if (header.rfind("t=", 0) != 0 || comma == std::string::npos) return false;
  const std::string t = header.substr(2, comma - 2);
  const std::string v1 = header.substr(comma + 4);
  const std::string text = t + "." + body;
  unsigned char mac[EVP_MAX_MD_SIZE];
  unsigned length = 0;
  HMAC(EVP_sha256(), secret.data(), static_cast<int>(secret.size()),
       reinterpret_cast<const unsigned char*>(text.data()), text.size(), mac, &length);
  std::string expected;
  char two[3];
  for (unsigned i = 0; i < length; ++i) {
    std::snprintf(two, sizeof two, "%02x", mac[i]);
    expected += two;
  }
  const double age = std::abs(static_cast<double>(std::time(nullptr)) - std::stod(t));
  return expected == v1 && age < 300;
}

// The job's status until its callback is no longer pending (or `seconds` passed).
json wait_callback_done(const Server& s, const std::string& id, int seconds = 30) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  json job;
  while (std::chrono::steady_clock::now() < end) {
    job = body(s.client().Get("/v1/jobs/" + id));
    if (job.contains("callback") && job["callback"]["state"] != "pending") return job;
    std::this_thread::sleep_for(50ms);
  }
  ADD_FAILURE() << "the callback of job " << id << " is still pending: " << job.dump();
  return job;
}

}  // namespace

TEST_P(ServeWebhooks, AListedReceiverGetsTheSignedFinalStatus) {
  Receiver receiver;
  Server s({"--workers", "1", "--webhook-hosts", "127.0.0.1", "--webhook-secret", kSecret});
  auto res = s.client().Post("/v1/jobs" + with_callback(receiver.url()), kTetraObj, "model/obj");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 202) << res->body;
  const std::string id = body(res)["id"];
  EXPECT_EQ(body(res)["options"]["callback_url"], receiver.url());

  const std::vector<Call> calls = receiver.wait_for(1);
  ASSERT_EQ(calls.size(), 1u) << s.log();
  EXPECT_TRUE(signature_valid(calls[0].signature, calls[0].body, kSecret)) << calls[0].signature;
  EXPECT_FALSE(signature_valid(calls[0].signature, calls[0].body + " ", kSecret));
  EXPECT_FALSE(signature_valid(calls[0].signature, calls[0].body, "another secret"));
  EXPECT_EQ(calls[0].job, id);
  const json sent = json::parse(calls[0].body);
  EXPECT_EQ(sent["id"], id);
  EXPECT_EQ(sent["status"], "succeeded");
  EXPECT_FALSE(sent["finished"].is_null());
  EXPECT_FALSE(sent.contains("callback"));

  const json job = wait_callback_done(s, id);
  EXPECT_EQ(job["callback"]["url"], receiver.url());
  EXPECT_EQ(job["callback"]["state"], "delivered");
  EXPECT_EQ(job["callback"]["delivered"], true);
  ASSERT_EQ(job["callback"]["attempts"].size(), 1u);
  EXPECT_EQ(job["callback"]["attempts"][0]["status"], 200);
  EXPECT_TRUE(job["callback"]["attempts"][0]["at"].is_string());
  EXPECT_NE(s.log().find("webhook job " + id + " attempt 1: HTTP 200"), std::string::npos)
      << s.log();

  // A job answered from a stored result ends at once: its callback goes too.
  auto again = s.client().Post("/v1/jobs" + with_callback(receiver.url() + "?again=1"), kTetraObj,
                               "model/obj");
  ASSERT_EQ(again->status, 202) << again->body;
  EXPECT_TRUE(body(again)["result"].is_object()) << again->body;  // reused
  const std::string reused = body(again)["id"];
  ASSERT_EQ(receiver.wait_for(2).size(), 2u);
  EXPECT_EQ(json::parse(receiver.calls()[1].body)["id"], reused);
  EXPECT_EQ(wait_callback_done(s, reused)["callback"]["state"], "delivered");
}

TEST_P(ServeWebhooks, LoopbackAndPrivateHostsAreRefusedUnlessListed) {
  Server open({"--workers", "1", "--webhook-secret", kSecret});
  for (const char* url :
       {"http://127.0.0.1:9/hook", "http://localhost/hook", "http://10.1.2.3/",
        "http://192.168.0.10/", "http://172.20.0.1/", "http://169.254.169.254/latest/meta-data",
        "http://[::1]:8080/", "http://0.0.0.0/", "http://100.64.0.1/"}) {
    SCOPED_TRACE(url);
    auto res = open.client().Post("/v1/jobs" + with_callback(url), kTetraObj, "model/obj");
    expect_problem(res, 422, "callback_url_refused");
    EXPECT_EQ(body(res)["option"], "callback_url");
  }
  // Malformed URLs: 400 naming the option.
  for (const char* url : {"https://hooks.example/", "ftp://hooks.example/",
                          "http://user@127.0.0.1/", "http://127.0.0.1:99999/", "hooks.example"}) {
    SCOPED_TRACE(url);
    auto res = open.client().Post("/v1/jobs" + with_callback(url), kTetraObj, "model/obj");
    expect_problem(res, 400, "invalid_option_value");
    EXPECT_EQ(body(res)["option"], "callback_url");
  }
  // The JSON options part is held to the same rules.
  httplib::MultipartFormDataItems parts = {
      {"mesh", kTetraObj, "tetra.obj", "model/obj"},
      {"options", R"({"callback_url": "http://127.0.0.1/hook"})", "", "application/json"}};
  auto multipart = open.client().Post("/v1/jobs", parts);
  expect_problem(multipart, 422, "callback_url_refused");
  EXPECT_EQ(body(open.client().Get("/v1/jobs"))["jobs"].size(), 0u);  // nothing was stored

  // With a list, only listed hosts: another loopback address is not 127.0.0.1.
  Server listed({"--workers", "1", "--webhook-hosts", "127.0.0.1", "--webhook-secret", kSecret});
  auto other = listed.client().Post("/v1/jobs" + with_callback("http://127.0.0.2/hook"), kTetraObj,
                                    "model/obj");
  expect_problem(other, 422, "callback_url_refused");
  EXPECT_NE(body(other)["detail"].get<std::string>().find("--webhook-hosts"), std::string::npos);
  // Without a secret no callback is accepted, listed or not.
  Server unsigned_server({"--workers", "1", "--webhook-hosts", "127.0.0.1"});
  auto no_secret = unsigned_server.client().Post(
      "/v1/jobs" + with_callback("http://127.0.0.1/hook"), kTetraObj, "model/obj");
  expect_problem(no_secret, 422, "callback_url_refused");
  EXPECT_NE(body(no_secret)["detail"].get<std::string>().find("--webhook-secret"),
            std::string::npos);
}

TEST_P(ServeWebhooks, AFailedAttemptIsRetriedAndEveryAttemptIsShown) {
  Receiver receiver;
  receiver.answer({500, 302}, 200);  // a redirect is not followed: it counts as a failure
  Server s({"--workers", "1", "--webhook-hosts", "127.0.0.1", "--webhook-secret", kSecret});
  const std::string id = submit(s, kTetraObj, "model/obj", with_callback(receiver.url()));
  const json job = wait_callback_done(s, id);
  EXPECT_EQ(job["callback"]["state"], "delivered") << job.dump();
  const json& attempts = job["callback"]["attempts"];
  ASSERT_EQ(attempts.size(), 3u) << job.dump();
  EXPECT_EQ(attempts[0]["status"], 500);
  EXPECT_EQ(attempts[1]["status"], 302);
  EXPECT_EQ(attempts[1]["error"], "redirect not followed");
  EXPECT_EQ(attempts[2]["status"], 200);
  EXPECT_EQ(receiver.redirected(), 0);
  const std::vector<Call> calls = receiver.calls();
  ASSERT_EQ(calls.size(), 3u);
  for (const Call& c : calls) EXPECT_TRUE(signature_valid(c.signature, c.body, kSecret));
  EXPECT_EQ(calls[0].body, calls[2].body);  // the same document, signed anew each time
  const std::string log = s.log();
  EXPECT_NE(log.find("webhook job " + id + " attempt 1: HTTP 500; next in 1 s"), std::string::npos)
      << log;
  EXPECT_NE(
      log.find("webhook job " + id + " attempt 2: HTTP 302 (redirect not followed); next in 2 s"),
      std::string::npos)
      << log;
}

TEST_P(ServeWebhooks, AHostThatNeverAnswersHoldsNoRequestAndIsRetriedBoundedly) {
  Silent silent;
  Receiver receiver;
  Server s({"--workers", "1", "--webhook-hosts", "127.0.0.1", "--webhook-secret", kSecret,
            "--webhook-timeout", "1", "--webhook-retry-for", "3"});
  const auto started = std::chrono::steady_clock::now();
  const std::string stuck = submit(s, kTetraObj, "model/obj", with_callback(silent.url()));
  wait_final(s, stuck);
  // While its callback waits on the silent host, requests are answered at once and another
  // job's callback goes out.
  for (int i = 0; i < 10; ++i) {
    const auto before = std::chrono::steady_clock::now();
    auto res = s.client().Get("/v1/jobs/" + stuck);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200);
    EXPECT_LT(std::chrono::steady_clock::now() - before, 500ms);
    std::this_thread::sleep_for(50ms);
  }
  const std::string other = submit(s, kTetraObj, "model/obj",
                                   "?strategy=TU&seed=2&callback_url=" + encode(receiver.url()));
  EXPECT_EQ(wait_callback_done(s, other)["callback"]["state"], "delivered");

  const json job = wait_callback_done(s, stuck);
  EXPECT_EQ(job["callback"]["state"], "failed") << job.dump();
  EXPECT_EQ(job["callback"]["delivered"], false);
  const json& attempts = job["callback"]["attempts"];
  // Attempts at 0, ~2 (1 s timeout, 1 s backoff) and maybe ~5: none starts 3 s after the first.
  EXPECT_GE(attempts.size(), 2u) << job.dump();
  EXPECT_LE(attempts.size(), 3u) << job.dump();
  for (const json& a : attempts) EXPECT_TRUE(a.contains("error")) << a.dump();
  EXPECT_LT(std::chrono::steady_clock::now() - started, 30s);
  EXPECT_NE(s.log().find("gave up"), std::string::npos) << s.log();
}

TEST_P(ServeWebhooks, ADeliveryPendingAtAStopIsDoneAfterTheRestart) {
  Receiver receiver;
  receiver.answer({}, 503);
  Server s({"--workers", "1", "--webhook-hosts", "127.0.0.1", "--webhook-secret", kSecret});
  const std::string id = submit(s, kTetraObj, "model/obj", with_callback(receiver.url()));
  ASSERT_GE(receiver.wait_for(1).size(), 1u) << s.log();
  EXPECT_EQ(s.stop(SIGTERM), 0);
  const std::size_t before = receiver.calls().size();

  receiver.answer({}, 200);
  s.start();
  const json job = wait_callback_done(s, id, 60);
  EXPECT_EQ(job["callback"]["state"], "delivered") << job.dump();
  const json& attempts = job["callback"]["attempts"];
  ASSERT_EQ(attempts.size(), before + 1) << job.dump();
  EXPECT_EQ(attempts[0]["status"], 503);
  EXPECT_EQ(attempts[before]["status"], 200);
}

TEST(WebhookAddresses, InternalRangesAreRecognised) {
  using papernet::server::is_internal_address;
  for (const char* a : {"127.0.0.1",
                        "127.255.0.9",
                        "10.0.0.1",
                        "172.16.0.1",
                        "172.31.255.255",
                        "192.168.1.1",
                        "169.254.169.254",
                        "100.64.0.1",
                        "0.0.0.0",
                        "224.0.0.1",
                        "255.255.255.255",
                        "::1",
                        "::",
                        "fd00::1",
                        "fe80::1",
                        "::ffff:127.0.0.1",
                        "::ffff:10.0.0.1",
                        "64:ff9b::a00:1",
                        "ff02::1",
                        "not an address"})
    EXPECT_TRUE(is_internal_address(a)) << a;
  for (const char* a : {"8.8.8.8", "1.1.1.1", "172.32.0.1", "100.128.0.1", "93.184.216.34",
                        "2001:4860:4860::8888", "::ffff:8.8.8.8"})
    EXPECT_FALSE(is_internal_address(a)) << a;
}

TEST(WebhookSignature, IsHmacSha256OfTimeDotBody) {
  // The value `printf '%s' '1700000000.{"a":1}' | openssl dgst -sha256 -hmac key` prints.
  const std::string header = papernet::server::webhook_signature("key", 1700000000, "{\"a\":1}");
  EXPECT_EQ(header,
            "t=1700000000,v1=a438e398bfafc57e4396bb7fc2304422f0f768e965d073ca313cb52e22e6ad03");
}
