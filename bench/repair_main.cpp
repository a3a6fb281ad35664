// papernet-repair-bench [--faces N,N,...]: the time and peak memory of mesh repair
// (core/mesh/repair.h) on meshes of 10^4, 10^5 and 10^6 faces with defects of every kind, each
// size in a child process of its own so that its peak memory is its own. Prints figures; it is
// not a test (docs/performance.md).
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/mesh/repair.h"

namespace papernet::bench {
namespace {

// A torus of about `faces` faces (n x m quads split in two) with a defect of each kind every
// so often: flipped faces, duplicate faces, caps (a vertex on an edge, closed by a zero-area
// face), and a second torus touching it at one shared vertex (a pinch).
Mesh damaged_torus(std::size_t faces) {
  const int n = static_cast<int>(std::sqrt(faces / 2.0)), m = n;
  Mesh t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      t.vertices.push_back({(2 + 0.7 * std::cos(v)) * std::cos(u),
                            (2 + 0.7 * std::cos(v)) * std::sin(u), 0.7 * std::sin(v)});
    }
  const auto id = [&](int i, int j) { return ((i + n) % n) * m + (j + m) % m; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i * m + j) % 997 == 3) {
        // A cap: the quad's diagonal split at its middle, closed by a zero-area face.
        const Vec3 mid = 0.5 * (t.vertices[a] + t.vertices[c]);
        const int e = static_cast<int>(t.vertices.size());
        t.vertices.push_back(mid);
        t.faces.push_back({a, b, e});
        t.faces.push_back({e, b, c});
        t.faces.push_back({a, c, d});
        t.faces.push_back({a, e, c});
        continue;
      }
      t.faces.push_back({a, b, c});
      t.faces.push_back({a, c, d});
      if ((i * m + j) % 499 == 7) std::swap(t.faces.back()[1], t.faces.back()[2]);  // flipped
      if ((i * m + j) % 1009 == 11) t.faces.push_back(t.faces.back());              // duplicate
    }
  // A small second torus outside the first, touching it at the first's vertex 0, (2.7, 0, 0),
  // where both use that vertex: a pinch.
  const int base = static_cast<int>(t.vertices.size()), k = 8;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const double u = 2 * M_PI * i / k, v = 2 * M_PI * j / k;
      t.vertices.push_back({3.4 + (0.5 + 0.2 * std::cos(v)) * std::cos(u),
                            (0.5 + 0.2 * std::cos(v)) * std::sin(u), 0.2 * std::sin(v)});
    }
  const auto small = [&](int i, int j) {
    i = (i + k) % k, j = (j + k) % k;
    return i == k / 2 && j == 0 ? 0 : base + i * k + j;  // its vertex at (2.7, 0, 0) is vertex 0
  };
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      t.faces.push_back({small(i, j), small(i + 1, j), small(i + 1, j + 1)});
      t.faces.push_back({small(i, j), small(i + 1, j + 1), small(i, j + 1)});
    }
  return t;
}

long status_kb(const char* field) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(field, 0) == 0) return std::stol(line.substr(std::string(field).size()));
  return -1;
}

void measure(std::size_t faces) {
  const Mesh mesh = damaged_torus(faces);
  const long before = status_kb("VmRSS:");
  const auto start = std::chrono::steady_clock::now();
  const RepairResult r = repair_mesh(mesh);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::size_t parts = split_components(r.mesh).size();
  std::ostringstream repairs;
  for (const MeshRepair& m : r.repairs) repairs << " " << m.code << "=" << m.count;
  std::printf("| %zu | %.3f | %.0f | %.0f | %zu |%s |\n", mesh.faces.size(), seconds,
              before / 1024.0, status_kb("VmHWM:") / 1024.0, parts, repairs.str().c_str());
  std::fflush(stdout);
}

}  // namespace
}  // namespace papernet::bench

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes = {10'000, 100'000, 1'000'000};
  if (argc == 3 && std::string(argv[1]) == "--faces") {
    sizes.clear();
    std::istringstream list(argv[2]);
    for (std::string n; std::getline(list, n, ',');) sizes.push_back(std::stoul(n));
  } else if (argc != 1) {
    std::cerr << "usage: papernet-repair-bench [--faces N,N,...]\n";
    return 1;
  }
  std::printf("| faces | repair s | RSS before MB | peak RSS MB | parts | repairs |\n");
  std::printf("|---:|---:|---:|---:|---:|---|\n");
  std::fflush(stdout);
  for (std::size_t faces : sizes) {
    const pid_t child = fork();
    if (child == 0) {
      papernet::bench::measure(faces);
      _exit(0);
    }
    int status = 0;
    waitpid(child, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::cerr << "papernet-repair-bench: the run of " << faces << " faces failed\n";
      return 1;
    }
  }
  return 0;
}
