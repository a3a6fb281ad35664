// Live progress streams (GET /v1/jobs/{id}/events) by the hundred over real sockets: each is
// served, the service still answers while they are open, the one past --max-streams gets 429
// too_many_streams, a client that leaves frees its stream, and SIGTERM ends them all.
// Figures are printed ("[ figures  ]"); the asserts are about correctness, never speed.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <functional>
#include <iostream>

#include "tests/support/files.h"
#include "tests/support/postgres.h"
#include "tests/support/sanitized.h"
#include "tests/support/serve_http.h"
#include "tests/support/serve_process.h"

using namespace papernet::test;

class Streams : public BothStores {};
INSTANTIATE_BOTH_STORES(Streams);

namespace {

// Fewer under the sanitizers, whose threads cost much more (never none).
#ifdef PAPERNET_TEST_SANITIZED
constexpr std::size_t kStreams = 60;
#else
constexpr std::size_t kStreams = 500;  // the default --max-streams
#endif

using Clock = std::chrono::steady_clock;

// Event streams on raw sockets, all read from one thread: hundreds at once without a client
// thread each. Each asks the server to close the connection when its response ends.
class RawStreams {
 public:
  RawStreams(int port, const std::string& path, std::size_t n) {
    const std::string request =
        "GET " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
    for (std::size_t i = 0; i < n; ++i) {
      const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
      sockaddr_in addr{};
      addr.sin_family = AF_INET;
      addr.sin_port = htons(static_cast<std::uint16_t>(port));
      addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
      EXPECT_EQ(::send(fd, request.data(), request.size(), MSG_NOSIGNAL),
                static_cast<ssize_t>(request.size()));
      streams_.push_back({fd, {}, false});
    }
  }
  ~RawStreams() {
    for (const Stream& s : streams_)
      if (s.fd >= 0) ::close(s.fd);
  }
  RawStreams(const RawStreams&) = delete;
  RawStreams& operator=(const RawStreams&) = delete;

  // Reads until `enough(text, ended)` holds for every stream not closed here, or `seconds`
  // pass; returns for how many it holds.
  std::size_t read_until(const std::function<bool(const std::string&, bool)>& enough,
                         double seconds) {
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    for (;;) {
      std::vector<pollfd> polls;
      std::vector<Stream*> of;
      std::size_t done = 0, counted = 0;
      for (Stream& s : streams_) {
        if (s.fd < 0) continue;
        ++counted;
        if (enough(s.text, s.ended)) ++done;
        if (!s.ended) {
          polls.push_back({s.fd, POLLIN, 0});
          of.push_back(&s);
        }
      }
      if (done == counted || Clock::now() > end) return done;
      if (::poll(polls.data(), polls.size(), 50) <= 0) continue;
      char buffer[8192];
      for (std::size_t i = 0; i < polls.size(); ++i) {
        if (!polls[i].revents) continue;
        const ssize_t n = ::recv(of[i]->fd, buffer, sizeof buffer, 0);
        if (n <= 0)
          of[i]->ended = true;
        else
          of[i]->text.append(buffer, static_cast<std::size_t>(n));
      }
    }
  }
  // The first `n` clients leave.
  void close_first(std::size_t n) {
    for (std::size_t i = 0; i < n && i < streams_.size(); ++i) {
      ::close(streams_[i].fd);
      streams_[i].fd = -1;
    }
  }
  std::size_t count_starting(const std::string& prefix) const {
    return static_cast<std::size_t>(std::count_if(
        streams_.begin(), streams_.end(), [&](auto& s) { return s.text.rfind(prefix, 0) == 0; }));
  }

 private:
  struct Stream {
    int fd;
    std::string text;
    bool ended;
  };
  std::vector<Stream> streams_;
};

bool has_progress(const std::string& text, bool) {
  return text.find("\nevent: progress\n") != std::string::npos;
}

// papernet_http_open_streams as /metrics says now; -1 when it is missing.
long open_streams(const Server& s) {
  auto res = s.client().Get("/metrics");
  if (!res) return -1;
  const std::string name = "\npapernet_http_open_streams ";
  const auto at = res->body.find(name);
  return at == std::string::npos ? -1 : std::stol(res->body.substr(at + name.size()));
}

// Polls until the gauge shows `n` (or 20 s pass); returns what it showed last.
long wait_open_streams(const Server& s, long n) {
  long now = -1;
  for (int i = 0; i < 400 && (now = open_streams(s)) != n; ++i) std::this_thread::sleep_for(50ms);
  return now;
}

std::string long_job(const Server& s) {
  const std::string id = submit(s, test_mesh("Duck.glb"), "model/gltf-binary",
                                "?detail=full&strategy=TU&time_limit=60&colour=none");
  wait_running(s, id);
  return id;
}

}  // namespace

TEST_P(Streams, HundredsOpenAtOnceAreServedAndTheServiceStillAnswers) {
  Server s({"--workers", "1", "--http-threads", "8", "--max-streams", std::to_string(kStreams),
            "--reuse-results", "false"});
  const std::string busy = long_job(s);
  const auto opening = Clock::now();
  RawStreams streams(s.port(), "/v1/jobs/" + busy + "/events", kStreams);
  EXPECT_EQ(streams.read_until(has_progress, 60), kStreams) << "every stream gets its first event";
  const double all_open = std::chrono::duration<double>(Clock::now() - opening).count();
  EXPECT_EQ(streams.count_starting("HTTP/1.1 200 OK\r\n"), kStreams);
  EXPECT_EQ(open_streams(s), static_cast<long>(kStreams));

  // Status polls are served while every stream is open (by threads the streams cannot take).
  auto c = s.client();
  std::vector<double> ms;
  for (int i = 0; i < 20; ++i) {
    const auto start = Clock::now();
    auto res = c.Get("/v1/jobs/" + busy);
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200);
  }
  std::sort(ms.begin(), ms.end());
  std::cout << "[ figures  ] " << kStreams << " streams had their first event after " << all_open
            << " s; status polls with them open: median " << ms[ms.size() / 2] << " ms, slowest "
            << ms.back() << " ms\n";

  // One past the cap: a clear 429.
  auto over = c.Get("/v1/jobs/" + busy + "/events");
  expect_problem(over, 429, "too_many_streams");
  EXPECT_EQ(over->get_header_value("Retry-After"), "5");

  // Clients that leave free their streams, and new ones open.
  const std::size_t leaving = kStreams / 2;
  streams.close_first(leaving);
  EXPECT_EQ(wait_open_streams(s, static_cast<long>(kStreams - leaving)),
            static_cast<long>(kStreams - leaving));
  RawStreams more(s.port(), "/v1/jobs/" + busy + "/events", 2);
  EXPECT_EQ(more.read_until(has_progress, 30), 2u);

  // The job's end ends every stream, with its final state.
  EXPECT_EQ(c.Delete("/v1/jobs/" + busy)->status, 202);
  const auto done = [](const std::string& text, bool ended) {
    return ended && text.find("\nevent: done\n") != std::string::npos;
  };
  EXPECT_EQ(streams.read_until(done, 30), kStreams - leaving);
  EXPECT_EQ(more.read_until(done, 30), 2u);
  EXPECT_EQ(wait_open_streams(s, 0), 0);
}

TEST_P(Streams, ShutdownWithStreamsOpenEndsThemAndExits) {
  Server s({"--workers", "1", "--max-streams", std::to_string(kStreams), "--shutdown-grace", "1",
            "--reuse-results", "false"});
  const std::string busy = long_job(s);
  RawStreams streams(s.port(), "/v1/jobs/" + busy + "/events", kStreams);
  ASSERT_EQ(streams.read_until(has_progress, 60), kStreams);

  const auto start = Clock::now();
  const int status = s.stop_within(SIGTERM, 30);
  const double took = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_TRUE(status >= 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0)
      << "status " << status << "; log:\n"
      << s.log();
  EXPECT_EQ(streams.read_until([](const std::string&, bool ended) { return ended; }, 5), kStreams)
      << "every stream is closed";
  std::cout << "[ figures  ] SIGTERM with " << kStreams << " streams open: exited after " << took
            << " s (--shutdown-grace 1)\n";
}
