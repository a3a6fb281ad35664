// papernet-stream-bench: what open live progress streams (GET /v1/jobs/{id}/events) cost the
// service on this machine, and what API keys cost a status poll (docs/reliability.md). It
// starts `papernet serve` on loopback (the program of this build, SQLite) and prints:
//   - for each N of --streams: N streams opened at once on a job that runs throughout (the
//     only worker busy, every stream getting up to ten events a second), the time until each
//     had its first event, then status polls (GET /v1/jobs/{id}, one keep-alive connection,
//     back to back) while they are open: p50, p99 and the slowest, with the server's threads,
//     resident memory and CPU over the polling;
//   - status polls per second from --connections keep-alive connections for --seconds, without
//     API keys and with a key file (each request then hashes and looks up its key).
// It prints figures; it asserts nothing.
//
//   papernet-stream-bench [--streams 0,50,200,500] [--polls 500] [--seconds 5]
//                         [--connections 4] [--repeat 3] [--papernet PATH] [--data DIR]
#include <arpa/inet.h>
#include <httplib.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/serve_node.h"
#include "server/api_keys.h"

namespace {

using papernet::bench::cpu_seconds;
using papernet::bench::read_file;
using papernet::bench::ServeNode;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;
using namespace std::chrono_literals;

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// A field of /proc/PID/status (VmRSS, Threads), as written there.
std::string proc_status(pid_t pid, const std::string& field) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(field + ":", 0) == 0) {
      const auto start = line.find_first_not_of(" \t", field.size() + 1);
      return start == std::string::npos ? "" : line.substr(start);
    }
  return "?";
}

struct Settings {
  std::vector<std::size_t> streams = {0, 50, 200, 500};
  int polls = 500, connections = 4, repeat = 3;
  double seconds = 5;
  std::string program = PAPERNET_PROGRAM, data;
};

// One `papernet serve` of the benchmark's settings (one worker), data under `name`.
class Node : public ServeNode {
 public:
  Node(const Settings& settings, const std::string& name, std::vector<std::string> flags)
      : ServeNode(settings.program, fs::path(settings.data) / name,
                  arguments(fs::path(settings.data) / name, std::move(flags))) {}

 private:
  static std::vector<std::string> arguments(const fs::path& dir, std::vector<std::string> flags) {
    std::vector<std::string> args = {"--port",       "0",     "--data",    dir.string(),
                                     "--access-log", "false", "--workers", "1"};
    args.insert(args.end(), flags.begin(), flags.end());
    return args;
  }
};

std::string submit(const Node& node, const std::string& mesh, const std::string& query,
                   const httplib::Headers& headers = {}) {
  auto res = node.client().Post("/v1/jobs" + query, headers, mesh, "application/octet-stream");
  if (!res || res->status != 202)
    throw std::runtime_error("submit failed: " + (res ? res->body : std::string("no answer")));
  return json::parse(res->body)["id"];
}

std::string status(const Node& node, const std::string& id, const httplib::Headers& h = {}) {
  auto res = node.client().Get("/v1/jobs/" + id, h);
  return res && res->status == 200 ? json::parse(res->body)["status"].get<std::string>() : "?";
}

// N event streams on raw sockets, read from one thread (what arrives is counted, not kept).
class Streams {
 public:
  Streams(int port, const std::string& path, std::size_t n) {
    const std::string request = "GET " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n";
    for (std::size_t i = 0; i < n; ++i) {
      const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
      sockaddr_in addr{};
      addr.sin_family = AF_INET;
      addr.sin_port = htons(static_cast<std::uint16_t>(port));
      addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
          ::send(fd, request.data(), request.size(), MSG_NOSIGNAL) < 0) {
        ::close(fd);
        continue;
      }
      fds_.push_back(fd);
      first_.push_back(false);
    }
  }
  ~Streams() {
    stop();
    for (int fd : fds_) ::close(fd);
  }
  // Reads until every stream had an event (or `seconds`); returns how many had one.
  std::size_t wait_first(double seconds) {
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < end &&
           std::count(first_.begin(), first_.end(), true) < static_cast<long>(first_.size()))
      read_once(true);
    return static_cast<std::size_t>(std::count(first_.begin(), first_.end(), true));
  }
  // Keeps reading (as browsers do) on a thread of its own until stop().
  void drain() {
    reader_ = std::thread([this] {
      while (!stop_) read_once(false);
    });
  }
  void stop() {
    stop_ = true;
    if (reader_.joinable()) reader_.join();
  }
  std::uint64_t bytes() const { return bytes_; }

 private:
  void read_once(bool look) {
    std::vector<pollfd> polls;
    for (int fd : fds_) polls.push_back({fd, POLLIN, 0});
    if (::poll(polls.data(), polls.size(), 50) <= 0) return;
    char buffer[16384];
    for (std::size_t i = 0; i < polls.size(); ++i) {
      if (!polls[i].revents) continue;
      const ssize_t n = ::recv(fds_[i], buffer, sizeof buffer, MSG_DONTWAIT);
      if (n <= 0) continue;
      bytes_ += static_cast<std::uint64_t>(n);
      if (look && std::string_view(buffer, static_cast<std::size_t>(n)).find("event: ") !=
                      std::string_view::npos)
        first_[i] = true;
    }
  }
  std::vector<int> fds_;
  std::vector<bool> first_;
  std::thread reader_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> bytes_{0};
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

void streams_and_polls(const Settings& s, const std::string& duck) {
  const std::size_t most = *std::max_element(s.streams.begin(), s.streams.end());
  std::cout << "\n## Status polls with N live streams open\n\n"
            << "One worker busy with one job (Duck.glb, TU, detail full) that every stream "
               "watches; "
            << s.polls << " polls back to back on one keep-alive connection.\n\n"
            << "| streams | all had a first event after | poll p50 | poll p99 | slowest | "
               "server threads | server RSS | server CPU while polling (the worker's included) | "
               "stream bytes/s |\n"
            << "|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t n : s.streams) {
    Node node(s, "streams-" + std::to_string(n),
              {"--max-streams", std::to_string(most), "--reuse-results", "false"});
    const std::string busy = submit(node, duck, "?detail=full&strategy=TU&time_limit=600");
    while (status(node, busy) == "queued") std::this_thread::sleep_for(10ms);
    const auto opening = Clock::now();
    Streams streams(node.port(), "/v1/jobs/" + busy + "/events", n);
    const std::size_t served = streams.wait_first(60);
    const double first = since(opening);
    streams.drain();
    std::this_thread::sleep_for(1s);  // settle: the stream threads wait, events flow
    auto c = node.client();
    std::vector<double> ms;
    const double cpu_before = cpu_seconds(node.pid());
    const std::uint64_t bytes_before = streams.bytes();
    const auto polling = Clock::now();
    int failed = 0;
    for (int i = 0; i < s.polls; ++i) {
      const auto start = Clock::now();
      auto res = c.Get("/v1/jobs/" + busy);
      ms.push_back(since(start) * 1000);
      failed += !res || res->status != 200;
    }
    const double wall = since(polling);
    const double cpu = cpu_seconds(node.pid()) - cpu_before;
    const double rate = static_cast<double>(streams.bytes() - bytes_before) / wall;
    const std::string still = status(node, busy);
    std::printf("| %zu%s | %.2f s | %.2f ms | %.2f ms | %.2f ms | %s | %s | %.0f %% | %.0f |\n",
                served, served == n ? "" : (" of " + std::to_string(n)).c_str(), first,
                percentile(ms, 0.5), percentile(ms, 0.99), percentile(ms, 1.0),
                proc_status(node.pid(), "Threads").c_str(),
                proc_status(node.pid(), "VmRSS").c_str(), 100 * cpu / wall, rate);
    if (failed || still != "running")
      std::cout << "  (" << failed << " polls failed; the job was " << still << " at the end)\n";
    std::cout.flush();
  }
}

double polls_per_second(const Settings& s, const Node& node, const std::string& id,
                        const httplib::Headers& headers) {
  std::atomic<long> ok{0}, bad{0};
  const auto end = Clock::now() + std::chrono::duration<double>(s.seconds);
  std::vector<std::thread> clients;
  for (int i = 0; i < s.connections; ++i)
    clients.emplace_back([&] {
      auto c = node.client();
      while (Clock::now() < end) {
        auto res = c.Get("/v1/jobs/" + id, headers);
        ++(res && res->status == 200 ? ok : bad);
      }
    });
  for (std::thread& t : clients) t.join();
  if (bad) std::cout << "  (" << bad << " polls failed)\n";
  return static_cast<double>(ok) / s.seconds;
}

void keys_on_and_off(const Settings& s, const std::string& mesh) {
  const fs::path keys = fs::path(s.data) / "keys.txt";
  const std::string secret = "bench-key-0123456789abcdef";
  std::ofstream(keys) << "bench " << papernet::server::sha256_hex(secret) << " name=bench\n";
  const httplib::Headers with_key = {{"Authorization", "Bearer " + secret}};
  std::cout << "\n## Status polls per second, API keys off and on\n\n"
            << s.connections << " keep-alive connections polling one finished job for " << s.seconds
            << " s; runs in turns.\n\n"
            << "| run | keys off | keys on |\n|---|---|---|\n";
  Node open(s, "keys-off", {});
  Node keyed(s, "keys-on", {"--api-keys", keys.string()});
  const std::string a = submit(open, mesh, "?strategy=TU");
  const std::string b = submit(keyed, mesh, "?strategy=TU", with_key);
  const auto final = [](const std::string& st) { return st != "queued" && st != "running"; };
  while (!final(status(open, a)) || !final(status(keyed, b, with_key)))
    std::this_thread::sleep_for(20ms);
  for (int round = 1; round <= s.repeat; ++round) {
    const double off = polls_per_second(s, open, a, {});
    const double on = polls_per_second(s, keyed, b, with_key);
    std::printf("| %d | %.0f/s | %.0f/s |\n", round, off, on);
    std::cout.flush();
  }
}

std::vector<std::size_t> counts(const std::string& list) {
  std::vector<std::size_t> out;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::stoul(item));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--streams")
      s.streams = counts(value);
    else if (flag == "--polls")
      s.polls = std::stoi(value);
    else if (flag == "--seconds")
      s.seconds = std::stod(value);
    else if (flag == "--connections")
      s.connections = std::stoi(value);
    else if (flag == "--repeat")
      s.repeat = std::stoi(value);
    else if (flag == "--papernet")
      s.program = value;
    else if (flag == "--data")
      s.data = value;
    else {
      std::cerr << "papernet-stream-bench: unknown flag " << flag << "\n";
      return 2;
    }
  }
  if (s.streams.empty() || s.polls < 1 || s.connections < 1) {
    std::cerr << "papernet-stream-bench: --streams, --polls and --connections need counts\n";
    return 2;
  }
  const bool own_data = s.data.empty();
  if (own_data)
    s.data = (fs::temp_directory_path() / ("papernet-stream-bench-" + std::to_string(getpid())))
                 .string();
  signal(SIGPIPE, SIG_IGN);
  try {
    const fs::path data_dir = PAPERNET_TEST_DATA;
    streams_and_polls(s, read_file(data_dir / "Duck.glb"));
    keys_on_and_off(s, read_file(data_dir / "sample.obj"));
  } catch (const std::exception& e) {
    std::cerr << "papernet-stream-bench: " << e.what() << "\n";
    if (own_data) fs::remove_all(s.data);
    return 1;
  }
  if (own_data) fs::remove_all(s.data);
  return 0;
}
