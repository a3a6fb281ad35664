#pragma once
// Small hand-made meshes for the unfolder's tests, built in code.

#include <cmath>
#include <vector>

#include "core/mesh.h"

namespace papernet::test {

/// Axis-aligned unit cube, 12 faces, closed, genus 0.
inline Mesh cube() {
  Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  m.faces = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
             {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  return m;
}

/// Torus of n x m quads split in two (genus 1, closed), radii R > r.
inline Mesh torus(int n, int m, double R = 2, double r = 0.7) {
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

/// Open height field z = h(x, y) over an n x n grid on [-1, 1]^2 (one boundary loop).
template <class Height>
Mesh height_field(int n, Height h) {
  Mesh g;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
      g.vertices.push_back({x, y, h(x, y)});
    }
  const auto id = [&](int i, int j) { return i * (n + 1) + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      g.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      g.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return g;
}

/// A saddle vertex: centre vertex 0, a ring of `n` vertices at alternating heights ±h (angle sum
/// at the centre well above 360°) and a flat outer ring. Faces 0..n-1 form the fan around the
/// centre, face i between ring vertices i and i+1; the outer band follows (2 faces per ring
/// edge). Open, one boundary loop.
inline Mesh saddle(int n = 8, double h = 0.3) {
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

/// An unfold tree of saddle(n) (parent per face, -1 at the root) whose fan around the centre is
/// one path, face i hanging from face i-1, so that the fan's angle sum above 360 degrees makes
/// its ends overlap; each outer band face pair hangs from its fan face.
inline std::vector<int> saddle_path_tree(int n = 8) {
  std::vector<int> parent(3 * n);
  for (int i = 0; i < n; ++i) parent[i] = i - 1;
  for (int i = 0; i < n; ++i) {
    parent[n + 2 * i] = n + 2 * i + 1;
    parent[n + 2 * i + 1] = i;
  }
  return parent;
}

}  // namespace papernet::test
