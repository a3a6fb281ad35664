// papernet_serve_load: a bounded load run against a running `papernet serve` on loopback.
// Fills the job queue (until 429), then hammers GET /v1/jobs/{id} from a few keep-alive
// connections for a fixed time and prints requests per second, status counts, latency
// percentiles and the server's resident memory before and after (from /proc/PID/status).
//
// With --slow N, N more connections send half a request head and then stall for the whole
// run (a slowloris); the figures then show what the other clients still get and how many of
// the stalled connections the server closed (--header-timeout / --read-timeout).
// With --burst N, N clients first submit one job each at the same moment (statuses counted).
//
//   papernet_serve_load --port 8080 --pid $(pidof papernet) [--seconds 10] [--connections 4]
//                       [--mesh tests/data/sample.obj] [--fill 200] [--slow 0] [--burst 0]
#include <httplib.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

std::string rss_of(const std::string& pid) {
  std::ifstream in("/proc/" + pid + "/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return line.substr(6);
  return " unknown";
}

// A connection that sends half a request head and then nothing.
int stalled_connection(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(fd);
    return -1;
  }
  const char head[] = "GET /healthz HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ";
  ::send(fd, head, sizeof head - 1, MSG_NOSIGNAL);
  return fd;
}

// True when the server has closed the connection (what it sent is read and dropped).
bool closed_by_server(int fd) {
  char buf[4096];
  for (;;) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 0) <= 0) return false;
    if (::recv(fd, buf, sizeof buf, 0) <= 0) return true;
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string host = "127.0.0.1", pid, mesh_path = "tests/data/sample.obj";
  int port = 8080, connections = 4, fill = 200, slow = 0, burst = 0;
  double seconds = 10;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--port")
      port = std::stoi(value);
    else if (flag == "--pid")
      pid = value;
    else if (flag == "--seconds")
      seconds = std::clamp(std::stod(value), 1.0, 60.0);
    else if (flag == "--connections")
      connections = std::clamp(std::stoi(value), 1, 32);
    else if (flag == "--mesh")
      mesh_path = value;
    else if (flag == "--fill")
      fill = std::clamp(std::stoi(value), 0, 10000);
    else if (flag == "--slow")
      slow = std::clamp(std::stoi(value), 0, 500);
    else if (flag == "--burst")
      burst = std::clamp(std::stoi(value), 0, 2000);
    else {
      std::cerr << "unknown flag " << flag << "\n";
      return 1;
    }
  }
  if (host != "127.0.0.1") return 1;  // loopback only, by construction
  std::ifstream in(mesh_path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string mesh = buffer.str();
  if (mesh.empty()) {
    std::cerr << "cannot read " << mesh_path << "\n";
    return 1;
  }
  if (!pid.empty()) std::cout << "server RSS before:" << rss_of(pid) << "\n";

  httplib::Client client(host, port);
  std::vector<std::string> ids;
  if (burst > 0) {
    std::mutex burst_mutex;
    std::map<int, int> burst_statuses;
    std::vector<std::thread> clients;
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < burst; ++i)
      clients.emplace_back([&, i] {
        httplib::Client c(host, port);
        c.set_connection_timeout(60, 0);
        c.set_read_timeout(60, 0);
        auto res =
            c.Post("/v1/jobs?strategy=TU&seed=" + std::to_string(500000 + i), mesh, "model/obj");
        std::lock_guard lock(burst_mutex);
        ++burst_statuses[res ? res->status : -1];
        if (res && res->status == 202) ids.push_back(nlohmann::json::parse(res->body)["id"]);
      });
    for (auto& t : clients) t.join();
    std::cout << "burst of " << burst << " concurrent POSTs in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
              << " s:";
    for (auto [s, k] : burst_statuses) std::cout << " " << k << " x " << s;
    std::cout << " (-1 = no answer)\n";
    if (!pid.empty()) std::cout << "server RSS after the burst:" << rss_of(pid) << "\n";
  }
  int refused = 0;
  for (int i = 0; i < fill; ++i) {
    auto res =
        client.Post("/v1/jobs?strategy=TU&seed=" + std::to_string(1000 + i), mesh, "model/obj");
    if (!res) {
      std::cerr << "server not reachable on port " << port << "\n";
      return 1;
    }
    if (res->status == 202) ids.push_back(nlohmann::json::parse(res->body)["id"]);
    if (res->status == 429) {
      ++refused;
      break;
    }
  }
  std::cout << "submitted " << ids.size() << " jobs; queue full (429): " << (refused ? "yes" : "no")
            << "\n";
  if (ids.empty()) return 1;
  if (!pid.empty()) std::cout << "server RSS with full queue:" << rss_of(pid) << "\n";

  std::vector<int> stalled;
  for (int i = 0; i < slow; ++i)
    if (const int fd = stalled_connection(port); fd >= 0) stalled.push_back(fd);
  if (slow > 0) std::cout << "holding " << stalled.size() << " stalled connections\n";
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::map<int, long> statuses;
  std::vector<double> latencies;
  std::vector<std::thread> threads;
  const auto start = std::chrono::steady_clock::now();
  for (int c = 0; c < connections; ++c)
    threads.emplace_back([&, c] {
      httplib::Client cli(host, port);
      cli.set_keep_alive(true);
      cli.set_read_timeout(60, 0);  // stalled connections may hold every HTTP thread a while
      cli.set_tcp_nodelay(true);
      std::map<int, long> mine;
      std::vector<double> lat;
      for (std::size_t n = static_cast<std::size_t>(c); !stop; n += 7) {
        const auto t0 = std::chrono::steady_clock::now();
        auto res = cli.Get("/v1/jobs/" + ids[n % ids.size()]);
        lat.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count());
        ++mine[res ? res->status : -1];
      }
      std::lock_guard lock(mutex);
      for (auto [s, k] : mine) statuses[s] += k;
      latencies.insert(latencies.end(), lat.begin(), lat.end());
    });
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  stop = true;
  for (auto& t : threads) t.join();
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::sort(latencies.begin(), latencies.end());
  auto pct = [&](double p) {
    return latencies[std::min(latencies.size() - 1,
                              static_cast<std::size_t>(p * static_cast<double>(latencies.size())))];
  };
  std::cout << "GET /v1/jobs/{id}: " << latencies.size() << " requests in " << elapsed
            << " s = " << static_cast<long>(static_cast<double>(latencies.size()) / elapsed)
            << " requests/s over " << connections << " connections\n";
  std::cout << "latency ms: p50 " << pct(0.5) << ", p99 " << pct(0.99) << ", max "
            << latencies.back() << "\n";
  for (auto [s, k] : statuses) std::cout << "status " << s << ": " << k << "\n";
  if (!pid.empty()) std::cout << "server RSS after:" << rss_of(pid) << "\n";
  if (!stalled.empty()) {
    const auto closed = std::count_if(stalled.begin(), stalled.end(), closed_by_server);
    std::cout << "stalled connections closed by the server: " << closed << " of " << stalled.size()
              << "\n";
    for (int fd : stalled) ::close(fd);
  }
  // Leave the server as we found it: cancel what we queued.
  for (const std::string& id : ids) client.Delete("/v1/jobs/" + id);
  return 0;
}
