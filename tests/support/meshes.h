#pragma once
// Small meshes built in code for the tests, and a plain breadth-first unfolder. The unfolder is
// deliberately simple (no overlap removal): the print writers must cope with any valid net.

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/unfold/net.h"

namespace papernet::test {

/// Regular tetrahedron, 4 faces, closed, outward counter-clockwise.
Mesh tetrahedron();
/// Axis-aligned unit cube, 12 faces, closed, genus 0.
Mesh cube();
/// Octahedron with its top vertex at (0, 0, top_z); below 0 it is dented.
Mesh octahedron(double top_z = 1);
/// Torus of n x m quads split in two (genus 1, closed), radii R > r.
Mesh torus(int n, int m, double R = 2, double r = 0.7);

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
Mesh saddle(int n = 8, double h = 0.3);

/// An unfold tree of saddle(n) (parent per face, -1 at the root) whose fan around the centre is
/// one path, face i hanging from face i-1, so that the fan's angle sum above 360 degrees makes
/// its ends overlap; each outer band face pair hangs from its fan face.
std::vector<int> saddle_path_tree(int n = 8);

/// A flat square platform (z = 0, open, one boundary loop) of side `size` > 1 with a fine k x k
/// grid on its corner [0, 1]^2 (2k^2 faces), two fans of k slivers each from the grid's top and
/// right sides to the far corners, and two giant triangles for the rest: 2k^2 + 2k + 2 faces, of
/// which each giant has about k^2 times the mean area (CAD parts have such faces).
Mesh platform(int k, double size);

/// A net of `mesh` by breadth-first search over faces from face 0: every child is laid out
/// across the edge it shares with its parent from the 3D edge lengths.
Net bfs_net(const Mesh& mesh);

/// Every mesh file of tests/data (all formats the loader reads), by file name.
std::vector<std::pair<std::string, Mesh>> test_data_meshes();

/// Standard base64 (RFC 4648, with padding) of bytes: glTF data URIs in the tests.
std::string base64(const std::string& bytes);

}  // namespace papernet::test
