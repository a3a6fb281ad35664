#include "tests/support/meshes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <queue>

#include "core/io/load.h"
#include "tests/support/paths.h"

namespace papernet::test {

Mesh tetrahedron() {
  Mesh m;
  m.vertices = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  m.faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  return m;
}

Mesh cube() {
  Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  m.faces = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
             {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  return m;
}

Mesh octahedron(double top_z) {
  Mesh m;
  m.vertices = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, top_z}, {0, 0, -1}};
  for (int i = 0; i < 4; ++i) {
    m.faces.push_back({i, (i + 1) % 4, 4});
    m.faces.push_back({(i + 1) % 4, i, 5});
  }
  return m;
}

Mesh torus(int n, int m, double R, double r) {
  Mesh t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      t.vertices.push_back({(R + r * std::cos(v)) * std::cos(u),
                            (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  const auto id = [&](int i, int j) { return (i % n) * m + (j % m); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      t.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return t;
}

Mesh saddle(int n, double h) {
  Mesh m;
  m.vertices.push_back({0, 0, 0});
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    m.vertices.push_back({std::cos(a), std::sin(a), i % 2 ? -h : h});
  }
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    m.vertices.push_back({2.5 * std::cos(a), 2.5 * std::sin(a), 0});
  }
  const auto ring = [n](int i) { return 1 + i % n; };
  const auto outer = [n](int i) { return 1 + n + i % n; };
  for (int i = 0; i < n; ++i) m.faces.push_back({0, ring(i), ring(i + 1)});
  for (int i = 0; i < n; ++i) {
    m.faces.push_back({ring(i), outer(i), outer(i + 1)});
    m.faces.push_back({ring(i), outer(i + 1), ring(i + 1)});
  }
  return m;
}

std::vector<int> saddle_path_tree(int n) {
  std::vector<int> parent(3 * n);
  for (int i = 0; i < n; ++i) parent[i] = i - 1;
  for (int i = 0; i < n; ++i) {
    parent[n + 2 * i] = n + 2 * i + 1;
    parent[n + 2 * i + 1] = i;
  }
  return parent;
}

Mesh platform(int k, double size) {
  Mesh m;
  const auto grid = [k](int i, int j) { return i * (k + 1) + j; };
  for (int i = 0; i <= k; ++i)
    for (int j = 0; j <= k; ++j) m.vertices.push_back({double(i) / k, double(j) / k, 0});
  const int a = static_cast<int>(m.vertices.size());  // (size, 0)
  m.vertices.push_back({size, 0, 0});
  m.vertices.push_back({size, size, 0});
  m.vertices.push_back({0, size, 0});
  const int b = a + 1, c = a + 2;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      m.faces.push_back({grid(i, j), grid(i + 1, j), grid(i + 1, j + 1)});
      m.faces.push_back({grid(i, j), grid(i + 1, j + 1), grid(i, j + 1)});
    }
  for (int j = 0; j < k; ++j) m.faces.push_back({a, grid(k, j + 1), grid(k, j)});
  for (int i = 0; i < k; ++i) m.faces.push_back({c, grid(i, k), grid(i + 1, k)});
  m.faces.push_back({grid(k, k), a, b});
  m.faces.push_back({grid(k, k), b, c});
  return m;
}

Net bfs_net(const Mesh& mesh) {
  const int n = static_cast<int>(mesh.faces.size());
  std::map<std::pair<int, int>, std::pair<int, int>> directed;  // (u, w) -> (face, k)
  for (int f = 0; f < n; ++f)
    for (int k = 0; k < 3; ++k) directed[{mesh.faces[f][k], mesh.faces[f][(k + 1) % 3]}] = {f, k};
  Net net;
  net.parent.assign(n, -2);
  net.points.resize(n);
  auto len = [&](int a, int b) { return norm(mesh.vertices[a] - mesh.vertices[b]); };
  auto lay = [&](int g, int k, Vec2 a, Vec2 b) {  // edge k of g from a to b, third on the left
    const auto& v = mesh.faces[g];
    const double d = norm(b - a), r1 = len(v[k], v[(k + 2) % 3]),
                 r2 = len(v[(k + 1) % 3], v[(k + 2) % 3]);
    const double along = (r1 * r1 - r2 * r2 + d * d) / (2 * d);
    const double h = std::sqrt(std::max(0.0, r1 * r1 - along * along));
    const Vec2 e = (1 / d) * (b - a), up{-e.y, e.x};
    net.points[g][k] = a;
    net.points[g][(k + 1) % 3] = b;
    net.points[g][(k + 2) % 3] = a + along * e + h * up;
  };
  for (int root = 0; root < n; ++root) {
    if (net.parent[root] != -2) continue;
    net.parent[root] = -1;
    const auto& v = mesh.faces[root];
    lay(root, 0, {0, 0}, {len(v[0], v[1]), 0});
    std::queue<int> todo;
    todo.push(root);
    while (!todo.empty()) {
      const int f = todo.front();
      todo.pop();
      for (int k = 0; k < 3; ++k) {
        const int u = mesh.faces[f][k], w = mesh.faces[f][(k + 1) % 3];
        const auto it = directed.find({w, u});
        if (it == directed.end()) continue;
        const auto [g, kg] = it->second;
        if (net.parent[g] != -2) continue;
        net.parent[g] = f;
        lay(g, kg, net.points[f][(k + 1) % 3], net.points[f][k]);
        todo.push(g);
      }
    }
  }
  return net;
}

std::vector<std::pair<std::string, Mesh>> test_data_meshes() {
  std::vector<std::pair<std::string, Mesh>> out;
  for (const auto& entry : std::filesystem::directory_iterator(papernet::test::test_data_dir())) {
    if (format_from_extension(entry.path().string()) == MeshFormat::Unknown) continue;
    out.emplace_back(entry.path().filename().string(), load_mesh_file(entry.path().string()).mesh);
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
}

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t n = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) n |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) n |= std::uint8_t(bytes[i + 2]);
    out += digits[(n >> 18) & 63];
    out += digits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[n & 63] : '=';
  }
  return out;
}

}  // namespace papernet::test
