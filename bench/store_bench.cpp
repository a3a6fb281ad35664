// papernet-store-bench: what the shared PostgreSQL store costs and gives on this machine
// (docs/scaling.md). It starts `papernet serve` nodes on loopback, with the SQLite store or
// sharing a PostgreSQL server (by default a throwaway one, started with scripts/test-postgres.sh
// with durable settings and TCP on loopback), and prints:
//   - jobs per second: N small jobs (the test meshes mirror.ply and testplate.glb, distinct
//     seeds) submitted at once, until every one has ended; SQLite and PostgreSQL on one node, in
//     turns, then PostgreSQL on two (submissions alternate, as behind a load balancer);
//   - status polls per second per node: C keep-alive connections per node for S seconds;
//   - cross-node cancel latency: DELETE sent to the node that does not run the job, until that
//     node answers "cancelled" (the running node saw it and stopped);
//   - cross-node progress latency: each phase change of a job as its node's event stream and the
//     other node's event stream show it, the second's arrival minus the first's.
// It prints figures; it asserts nothing.
//
//   papernet-store-bench [--jobs 60] [--workers 2] [--seconds 5] [--connections 4] [--repeat 3]
//                        [--rounds 5] [--postgres URL] [--papernet PATH] [--data DIR]
// (--repeat: one-node runs per store, in turns; --rounds: samples of each latency)
#include <httplib.h>
#include <signal.h>
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
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/serve_node.h"

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

// CPU seconds of a PostgreSQL server: the postmaster, its live processes and those it reaped.
double server_cpu_seconds(pid_t postmaster) {
  double total = cpu_seconds(postmaster, true);
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string stat = read_file(entry.path() / "stat");
    const auto paren = stat.rfind(')');
    if (paren == std::string::npos) continue;
    std::istringstream fields(stat.substr(paren + 2));
    std::string state;
    pid_t parent = 0;
    fields >> state >> parent;
    if (parent == postmaster) total += cpu_seconds(std::stoi(name));
  }
  return total;
}

struct Settings {
  int jobs = 60, workers = 2, connections = 4, rounds = 5, repeat = 3;
  double seconds = 5;
  std::string postgres, program = PAPERNET_PROGRAM, data;
};

// One `papernet serve` of the benchmark's settings, data under `name`.
class Node : public ServeNode {
 public:
  Node(const Settings& settings, const std::string& name, std::vector<std::string> flags)
      : ServeNode(settings.program, fs::path(settings.data) / name,
                  arguments(settings, fs::path(settings.data) / name, std::move(flags))) {}
  bool runs(const std::string& id) const {
    return log().find("job " + id + " queued -> running") != std::string::npos;
  }

 private:
  static std::vector<std::string> arguments(const Settings& settings, const fs::path& dir,
                                            std::vector<std::string> flags) {
    std::vector<std::string> args = {
        "--port",         "0",     "--data",    dir.string(),
        "--access-log",   "false", "--workers", std::to_string(settings.workers),
        "--queue-length", "100000"};
    args.insert(args.end(), flags.begin(), flags.end());
    return args;
  }
};

struct Meshes {
  std::string ply = read_file(fs::path(PAPERNET_TEST_DATA) / "mirror.ply");
  std::string glb = read_file(fs::path(PAPERNET_TEST_DATA) / "testplate.glb");
  std::string duck = read_file(fs::path(PAPERNET_TEST_DATA) / "Duck.glb");
};

std::string submit(const Node& node, const std::string& mesh, const std::string& query) {
  auto res = node.client().Post("/v1/jobs" + query, mesh, "application/octet-stream");
  if (!res || res->status != 202)
    throw std::runtime_error("submit failed: " + (res ? res->body : std::string("no answer")));
  return json::parse(res->body)["id"];
}

std::string status(const Node& node, const std::string& id) {
  auto res = node.client().Get("/v1/jobs/" + id);
  return res && res->status == 200 ? json::parse(res->body)["status"].get<std::string>() : "?";
}

// Jobs per second: all submitted at once (alternating between the nodes), until all ended.
double jobs_per_second(const Settings& s, const std::vector<const Node*>& nodes,
                       const Meshes& meshes, std::vector<std::string>& ids, int round) {
  const auto start = Clock::now();
  for (int i = 0; i < s.jobs; ++i)
    ids.push_back(submit(*nodes[static_cast<std::size_t>(i) % nodes.size()],
                         i % 2 ? meshes.glb : meshes.ply,
                         "?seed=" + std::to_string(round * 100000 + i + 1)));
  for (const std::string& id : ids)
    for (std::string st; (st = status(*nodes[0], id)) == "queued" || st == "running";)
      std::this_thread::sleep_for(50ms);  // a client polling its job, not a load on the store
  return s.jobs / since(start);
}

// Status polls per second of each node, all polled at once.
std::vector<double> polls_per_second(const Settings& s, const std::vector<const Node*>& nodes,
                                     const std::vector<std::string>& ids) {
  std::atomic<bool> stop{false};
  std::vector<std::atomic<long>> counts(nodes.size());
  std::atomic<long> failures{0};
  std::vector<std::thread> threads;
  for (std::size_t n = 0; n < nodes.size(); ++n)
    for (int c = 0; c < s.connections; ++c)
      threads.emplace_back([&, n, c] {
        auto client = nodes[n]->client();
        for (std::size_t k = static_cast<std::size_t>(c); !stop; k += 7) {
          auto res = client.Get("/v1/jobs/" + ids[k % ids.size()]);
          if (res && res->status == 200)
            ++counts[n];
          else
            ++failures;
        }
      });
  const auto start = Clock::now();
  std::this_thread::sleep_for(std::chrono::duration<double>(s.seconds));
  stop = true;
  for (std::thread& t : threads) t.join();
  const double elapsed = since(start);
  if (failures) std::cout << "  (" << failures << " polls failed)\n";
  std::vector<double> out;
  for (auto& c : counts) out.push_back(static_cast<double>(c) / elapsed);
  return out;
}

// Which of the two nodes runs the job (waits until one does).
std::size_t running_node(const std::vector<const Node*>& nodes, const std::string& id) {
  for (;;) {
    for (std::size_t n = 0; n < nodes.size(); ++n)
      if (nodes[n]->runs(id)) return n;
    std::this_thread::sleep_for(2ms);
  }
}

std::string one_decimal(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", v);
  return text;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

std::string summary(std::vector<double> v, const char* unit) {
  if (v.empty()) return "no samples";
  std::sort(v.begin(), v.end());
  char text[160];
  std::snprintf(text, sizeof text, "min %.0f %s, median %.0f %s, max %.0f %s (%zu samples)",
                v.front(), unit, v[v.size() / 2], unit, v.back(), unit, v.size());
  return text;
}

// DELETE on the other node, until it answers "cancelled".
std::vector<double> cancel_latencies(const Settings& s, const std::vector<const Node*>& nodes,
                                     const Meshes& meshes) {
  std::vector<double> ms;
  for (int r = 0; r < s.rounds; ++r) {
    const std::string id =
        submit(*nodes[0], meshes.duck, "?strategy=TU&seed=" + std::to_string(700 + r));
    const Node& other = *nodes[1 - running_node(nodes, id)];
    std::this_thread::sleep_for(300ms);
    const auto start = Clock::now();
    other.client().Delete("/v1/jobs/" + id);
    while (status(other, id) == "running") std::this_thread::sleep_for(1ms);
    ms.push_back(since(start) * 1000);
  }
  return ms;
}

// Phase changes in the running node's stream and in the other node's.
std::vector<double> progress_latencies(const Settings& s, const std::vector<const Node*>& nodes,
                                       const Meshes& meshes) {
  std::vector<double> ms;
  for (int r = 0; r < s.rounds; ++r) {
    const std::string id =
        submit(*nodes[0], meshes.duck, "?tab_room_budget=0&seed=" + std::to_string(800 + r));
    const std::size_t runner = running_node(nodes, id);
    std::map<std::string, Clock::time_point> seen[2];
    std::vector<std::thread> streams;
    for (std::size_t side = 0; side < 2; ++side)
      streams.emplace_back([&, side] {
        const Node& node = *nodes[side == 0 ? runner : 1 - runner];
        std::string text;
        node.client().Get("/v1/jobs/" + id + "/events", [&](const char* data, std::size_t n) {
          text.append(data, n);
          for (std::size_t at; (at = text.find("\n\n")) != std::string::npos;
               text.erase(0, at + 2)) {
            const auto data_at = text.find("data: ");
            if (data_at == std::string::npos || data_at > at) continue;
            const json doc =
                json::parse(text.substr(data_at + 6, at - data_at - 6), nullptr, false);
            if (!doc.is_object() || !doc["progress"]["phase"].is_string()) continue;
            seen[side].emplace(doc["progress"]["phase"].get<std::string>(), Clock::now());
          }
          return true;
        });
      });
    for (std::thread& t : streams) t.join();
    for (const auto& [phase, local] : seen[0])
      if (auto it = seen[1].find(phase);
          it != seen[1].end() && phase != "running" && phase != "queued" && phase != "done")
        ms.push_back(std::chrono::duration<double, std::milli>(it->second - local).count());
  }
  return ms;
}

// A throwaway PostgreSQL server: scripts/test-postgres.sh with durable settings, on TCP.
class Postgres {
 public:
  explicit Postgres(const std::string& dir) : dir_(dir) {
    const int port = 20000 + static_cast<int>(getpid() % 20000);
    const std::string cmd = "PG_DURABLE=1 bash " PAPERNET_SOURCE_DIR
                            "/scripts/test-postgres.sh start " +
                            dir_ + " " + std::to_string(port) + " > /dev/null";
    if (std::system(cmd.c_str()) != 0) throw std::runtime_error("cannot start PostgreSQL: " + cmd);
    url_ = "postgresql://postgres@127.0.0.1:" + std::to_string(port) + "/";
  }
  ~Postgres() {
    const std::string cmd =
        "bash " PAPERNET_SOURCE_DIR "/scripts/test-postgres.sh destroy " + dir_ + " > /dev/null";
    if (std::system(cmd.c_str()) != 0) std::cerr << "could not remove " << dir_ << "\n";
  }
  const std::string& url() const { return url_; }
  pid_t postmaster() const {
    return std::stoi(read_file(fs::path(dir_) / "data" / "postmaster.pid"));
  }

 private:
  std::string dir_, url_;
};

// A new database on the server (through psql, as the benchmark's nodes will use it).
std::string new_database(const std::string& server_url, const std::string& name) {
  const std::string cmd = "psql -q -X '" + server_url + "postgres' -c 'DROP DATABASE IF EXISTS " +
                          name + "' -c 'CREATE DATABASE " + name + "' > /dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("cannot create " + name);
  return server_url + name;
}

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--jobs")
      s.jobs = std::clamp(std::stoi(value), 2, 10000);
    else if (flag == "--workers")
      s.workers = std::clamp(std::stoi(value), 1, 64);
    else if (flag == "--seconds")
      s.seconds = std::clamp(std::stod(value), 1.0, 120.0);
    else if (flag == "--connections")
      s.connections = std::clamp(std::stoi(value), 1, 64);
    else if (flag == "--repeat")
      s.repeat = std::clamp(std::stoi(value), 1, 20);
    else if (flag == "--rounds")
      s.rounds = std::clamp(std::stoi(value), 1, 100);
    else if (flag == "--postgres")
      s.postgres = value;
    else if (flag == "--papernet")
      s.program = value;
    else if (flag == "--data")
      s.data = value;
    else {
      std::cerr << "unknown flag " << flag << " (see the comment at the top of store_bench.cpp)\n";
      return 2;
    }
  }
  if (s.data.empty())
    s.data =
        (fs::temp_directory_path() / ("papernet-store-bench-" + std::to_string(getpid()))).string();
  fs::create_directories(s.data);
  const Meshes meshes;
  try {
    std::unique_ptr<Postgres> own;
    if (s.postgres.empty()) own = std::make_unique<Postgres>(s.data + "/postgres");
    const std::string server = own ? own->url() : s.postgres;
    std::cout << "papernet-store-bench: " << s.jobs << " jobs, " << s.workers
              << " workers per node, " << s.connections << " poll connections per node for "
              << s.seconds << " s, " << s.rounds << " rounds of latencies; "
              << std::thread::hardware_concurrency() << " cores\n";

    // One node, SQLite and PostgreSQL in turns (the machine's load drifts), each on a new store.
    std::vector<std::string> ids;
    std::vector<double> rates[2], poll_rates[2], cpu[2];
    for (int r = 0; r < s.repeat; ++r)
      for (int pg = 0; pg < 2; ++pg) {
        ids.clear();
        const std::string name = (pg ? "pg-" : "sqlite-") + std::to_string(r);
        std::vector<std::string> flags;
        if (pg) flags = {"--store", new_database(server, "bench_" + std::to_string(r))};
        Node node(s, name, flags);
        const double node_cpu = cpu_seconds(node.pid());
        const double db_cpu = pg && own ? server_cpu_seconds(own->postmaster()) : 0;
        rates[pg].push_back(jobs_per_second(s, {&node}, meshes, ids, 10 + 2 * r + pg));
        const double node_ms = (cpu_seconds(node.pid()) - node_cpu) * 1000 / s.jobs;
        const double db_ms =
            pg && own ? (server_cpu_seconds(own->postmaster()) - db_cpu) * 1000 / s.jobs : 0;
        cpu[pg].push_back(node_ms + db_ms);
        poll_rates[pg].push_back(polls_per_second(s, {&node}, ids)[0]);
        std::cout << (pg ? "PostgreSQL" : "SQLite    ") << ", 1 node, round " << r + 1 << ": "
                  << rates[pg].back() << " jobs/s, CPU " << node_ms << " ms per job in papernet"
                  << (pg && own ? " + " + one_decimal(db_ms) + " ms in PostgreSQL" : "")
                  << "; status polls " << poll_rates[pg].back() << "/s\n";
      }
    std::cout << "1 node, median of " << s.repeat << ": SQLite " << median(rates[0])
              << " jobs/s, PostgreSQL " << median(rates[1]) << " jobs/s ("
              << 100 * (median(rates[1]) / median(rates[0]) - 1) << " %); status polls SQLite "
              << median(poll_rates[0]) << "/s, PostgreSQL " << median(poll_rates[1])
              << "/s; CPU per job SQLite " << median(cpu[0]) << " ms, PostgreSQL (papernet and "
              << "database) " << median(cpu[1]) << " ms\n";
    ids.clear();
    const std::string shared = new_database(server, "bench_two");
    Node a(s, "pg-a", {"--store", shared}), b(s, "pg-b", {"--store", shared});
    const double rate = jobs_per_second(s, {&a, &b}, meshes, ids, 3);
    const auto polls = polls_per_second(s, {&a, &b}, ids);
    std::cout << "PostgreSQL, 2 nodes:  " << rate << " jobs/s; status polls " << polls[0]
              << "/s and " << polls[1] << "/s (both polled at once)\n";
    std::cout << "cross-node cancel (DELETE on the other node until it answers cancelled): "
              << summary(cancel_latencies(s, {&a, &b}, meshes), "ms") << "\n";
    std::cout << "cross-node progress (a phase change in the other node's event stream, after "
                 "the running node's): "
              << summary(progress_latencies(s, {&a, &b}, meshes), "ms") << "\n";
  } catch (const std::exception& e) {
    std::cerr << "papernet-store-bench: " << e.what() << "\n";
    return 1;
  }
  fs::remove_all(s.data);
  return 0;
}
