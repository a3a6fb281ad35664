#include "core/mesh/thin_plates.h"

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/mesh/dual_graph.h"
#include "core/union_find.h"

namespace papernet {
namespace {

// Two faces are of one sheet when the fold between them is under 60 degrees: the cosine of the
// angle between their normals is above this.
constexpr double kSheetFoldCos = 0.5;

// The shares of the area a side of a plate holds: a flat plate's top holds about half, less its
// walls; a cube's side holds a sixth, and a sheet of nearly all of an open surface (all but a
// flap folded at its rim) is no side of a plate.
constexpr double kLeastSideShare = 1.0 / 3;
constexpr double kMostSideShare = 0.6;

// A vertex whose angles add up to 360 degrees within this (radians) is flat.
constexpr double kFlatAngle = 1e-4;

// True when the faces `keep` marks are one fan at each of their vertices (two fans of them that
// touch at a vertex are not manifold there). Around a vertex of a manifold mesh the faces are one
// chain or cycle: n of them kept, with e edges at the vertex between two kept faces, make n - e
// fans (one when all of a cycle is kept, n = e).
bool one_fan_at_each_vertex(const Mesh& mesh, const DualGraph& graph,
                            const std::vector<char>& keep) {
  std::vector<int> fans(mesh.vertices.size(), 0);
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) {
    if (!keep[f]) continue;
    for (int k = 0; k < 3; ++k) {
      ++fans[mesh.faces[f][k]];
      const int g = graph.neighbour[f][k];
      if (g > f && keep[g]) {
        --fans[mesh.faces[f][k]];
        --fans[mesh.faces[f][(k + 1) % 3]];
      }
    }
  }
  for (const int n : fans)
    if (n > 1) return false;
  return true;
}

}  // namespace

std::optional<Mesh> plate_side(const Mesh& mesh) {
  const DualGraph graph = build_dual_graph(mesh);
  const auto nf = static_cast<int>(mesh.faces.size());
  std::vector<Vec3> unit(mesh.faces.size());
  double total = 0;
  for (int f = 0; f < nf; ++f) {
    const Vec3 n = face_normal(mesh, f);
    const double length = norm(n);
    unit[f] = length > 0 ? (1 / length) * n : Vec3{0, 0, 0};
    total += 0.5 * length;
  }
  UnionFind sheet(mesh.faces.size());
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int g = graph.neighbour[f][k];
      if (g > f && dot(unit[f], unit[g]) > kSheetFoldCos) sheet.unite(f, g);
    }
  std::vector<double> area(mesh.faces.size(), 0);
  for (int f = 0; f < nf; ++f) area[sheet.find(f)] += face_area(mesh, f);
  // Of the sides (sheets of a share between the two), the one with fewest vertices inside it
  // that are not flat (each needs a cut to lie flat: the apex of a low pyramid), then the larger.
  // A vertex is inside a sheet when all its faces are of the sheet and it is on no boundary.
  std::vector<int> curved(mesh.faces.size(), 0);
  {
    std::vector<double> angles(mesh.vertices.size(), 0);
    std::vector<int> sheet_at(mesh.vertices.size(), -1);
    for (int f = 0; f < nf; ++f)
      for (const int v : mesh.faces[f]) {
        // -1: no face yet; -2: faces of two sheets (a vertex on a sheet's rim).
        int& s = sheet_at[v];
        s = s == -1 || s == sheet.find(f) ? sheet.find(f) : -2;
      }
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const auto& t = mesh.faces[f];
        const Vec3 a = mesh.vertices[t[k]], b = mesh.vertices[t[(k + 1) % 3]];
        const Vec3 c = mesh.vertices[t[(k + 2) % 3]];
        angles[t[k]] += std::atan2(norm(cross(b - a, c - a)), dot(b - a, c - a));
      }
    const std::vector<char> rim = boundary_vertices(mesh, graph);
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      if (sheet_at[v] >= 0 && !rim[v] && std::abs(angles[v] - 2 * std::numbers::pi) > kFlatAngle)
        ++curved[sheet_at[v]];
  }
  int side = -1;
  for (int f = 0; f < nf; ++f) {
    if (sheet.find(f) != f || !(area[f] >= kLeastSideShare * total) ||
        area[f] > kMostSideShare * total)
      continue;
    if (side < 0 || curved[f] < curved[side] || (curved[f] == curved[side] && area[f] > area[side]))
      side = f;
  }
  if (side < 0) return std::nullopt;
  std::vector<char> keep(mesh.faces.size(), 0);
  for (int f = 0; f < nf; ++f) keep[f] = sheet.find(f) == side;
  if (!one_fan_at_each_vertex(mesh, graph, keep)) return std::nullopt;
  std::vector<int> kept;
  for (int f = 0; f < nf; ++f)
    if (keep[f]) kept.push_back(f);
  return mesh_of_faces(mesh, kept);
}

}  // namespace papernet
