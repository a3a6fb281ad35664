// Validation on small meshes built here: each fault found, counted and located; genus and
// boundary loops from the Euler characteristic.
#include "core/mesh/validate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace papernet {
namespace {

Mesh tetrahedron() {
  Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

/// An n x m grid on a torus (genus 1), or on an open cylinder when `close` is false.
Mesh torus(int n, int m, bool close = true) {
  Mesh t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      t.vertices.push_back(
          {(3 + std::cos(v)) * std::cos(u), (3 + std::cos(v)) * std::sin(u), std::sin(v)});
    }
  for (int i = 0; i < (close ? n : n - 1); ++i)
    for (int j = 0; j < m; ++j) {
      const int a = i * m + j, b = ((i + 1) % n) * m + j, c = ((i + 1) % n) * m + (j + 1) % m,
                d = i * m + (j + 1) % m;
      t.faces.push_back({a, b, c});
      t.faces.push_back({a, c, d});
    }
  return t;
}

const MeshProblem* find(const ValidationReport& r, const std::string& code) {
  for (const MeshProblem& p : r.problems)
    if (p.code == code) return &p;
  return nullptr;
}

TEST(Validate, ClosedTetrahedronIsUnfoldableGenusZero) {
  const ValidationReport r = validate(tetrahedron());
  EXPECT_TRUE(r.unfoldable()) << r.reason();
  EXPECT_EQ(r.vertices, 4u);
  EXPECT_EQ(r.faces, 4u);
  EXPECT_EQ(r.edges, 6u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.genus, 0);
  EXPECT_EQ(r.boundary_loops, 0u);
  EXPECT_TRUE(r.problems.empty());
}

TEST(Validate, TorusHasGenusOneAndAnOpenTubeTwoBoundaries) {
  const ValidationReport closed = validate(torus(8, 6));
  EXPECT_TRUE(closed.unfoldable()) << closed.reason();
  EXPECT_EQ(closed.genus, 1);
  EXPECT_EQ(closed.boundary_loops, 0u);
  const ValidationReport open = validate(torus(8, 6, false));
  EXPECT_TRUE(open.unfoldable()) << open.reason();
  EXPECT_EQ(open.genus, 0);
  EXPECT_EQ(open.boundary_loops, 2u);
  EXPECT_EQ(open.boundary_edges, 12u);
}

TEST(Validate, OpenTetrahedronHasOneBoundaryLoop) {
  Mesh m = tetrahedron();
  m.faces.pop_back();
  const ValidationReport r = validate(m);
  EXPECT_TRUE(r.unfoldable());
  EXPECT_EQ(r.boundary_loops, 1u);
  EXPECT_EQ(r.boundary_edges, 3u);
  EXPECT_EQ(r.genus, 0);
}

TEST(Validate, EmptyMesh) {
  const ValidationReport r = validate(Mesh{});
  EXPECT_FALSE(r.unfoldable());
  ASSERT_NE(find(r, "empty_mesh"), nullptr);
  EXPECT_EQ(r.reason(), "the mesh has no faces");
}

TEST(Validate, NonFiniteCoordinatesAreLocated) {
  Mesh m = tetrahedron();
  m.vertices[2].y = std::numeric_limits<double>::quiet_NaN();
  const ValidationReport r = validate(m);
  EXPECT_FALSE(r.unfoldable());
  const MeshProblem* p = find(r, "non_finite_coordinates");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->elements, std::vector<int>{2});
  EXPECT_EQ(p->message, "1 vertex has non-finite coordinates: vertices 2 (0, nan, 0)");
}

TEST(Validate, DegenerateFacesAreCountedAndNamed) {
  Mesh m = tetrahedron();
  m.vertices.push_back({0.5, 0.5, 0});  // on the edge 1-2: face (1, 4, 2) is flat
  m.faces.push_back({1, 4, 2});
  m.faces.push_back({0, 0, 3});  // a repeated vertex
  const ValidationReport r = validate(m);
  const MeshProblem* p = find(r, "degenerate_faces");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->elements, (std::vector<int>{4, 5}));
  EXPECT_EQ(p->message, "2 degenerate faces (zero area or a repeated vertex): faces 4, 5");
  EXPECT_FALSE(r.unfoldable());
}

TEST(Validate, FacesWithARepeatedVertexStayOutOfTheTopology) {
  Mesh m = tetrahedron();
  m.faces.push_back({0, 0, 3});
  const ValidationReport r = validate(m);
  ASSERT_EQ(r.problems.size(), 1u) << r.problems[1].message;
  EXPECT_EQ(r.problems[0].code, "degenerate_faces");
  EXPECT_EQ(r.genus, 0);
  EXPECT_EQ(r.boundary_loops, 0u);
  EXPECT_EQ(r.edges, 6u);
}

TEST(Validate, SmallButWellShapedFacesAreNotDegenerate) {
  Mesh m = tetrahedron();
  for (auto& v : m.vertices) v = 1e-6 * v;
  m.vertices.push_back({1e6, 1e6, 1e6});  // unused, but makes the bounding box huge
  EXPECT_TRUE(validate(m).unfoldable()) << validate(m).reason();
}

TEST(Validate, NonManifoldEdgeIsLocated) {
  Mesh m = tetrahedron();
  m.vertices.push_back({1, 1, 1});
  m.faces.push_back({0, 1, 4});  // a third face on edge 0-1
  const ValidationReport r = validate(m);
  const MeshProblem* p = find(r, "non_manifold_edges");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->elements, (std::vector<int>{0, 1}));
  EXPECT_EQ(p->message, "1 edge is shared by more than two faces: edges 0-1 (0, 0, 0)-(1, 0, 0)");
  EXPECT_FALSE(r.unfoldable());
}

TEST(Validate, PinchedVertexIsNonManifold) {
  // Two tetrahedra touching at one vertex: one component, but vertex 0 is a pinch.
  Mesh m = tetrahedron();
  const int base = int(m.vertices.size());
  for (int i = 1; i < 4; ++i) m.vertices.push_back(-1.0 * m.vertices[i]);
  auto map = [&](int v) { return v == 0 ? 0 : base + v - 1; };
  for (const auto& f : tetrahedron().faces) m.faces.push_back({map(f[0]), map(f[2]), map(f[1])});
  const ValidationReport r = validate(m);
  EXPECT_EQ(r.components, 1u);
  const MeshProblem* p = find(r, "non_manifold_vertices");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->elements, std::vector<int>{0});
  EXPECT_NE(p->message.find("1 vertex joins"), std::string::npos) << p->message;
  EXPECT_FALSE(r.unfoldable());
}

TEST(Validate, FlippedFaceIsInconsistentOrientation) {
  Mesh m = tetrahedron();
  std::swap(m.faces[3][0], m.faces[3][1]);
  const ValidationReport r = validate(m);
  const MeshProblem* p = find(r, "inconsistent_orientation");
  ASSERT_NE(p, nullptr);
  EXPECT_NE(p->message.find("3 edges have"), std::string::npos) << p->message;
  EXPECT_EQ(p->elements.size(), 6u);
  EXPECT_FALSE(r.unfoldable());
}

TEST(Validate, SeveralComponentsOrTheLargest) {
  Mesh m = torus(6, 4);
  const Mesh t = tetrahedron();
  const int base = int(m.vertices.size());
  for (Vec3 v : t.vertices) m.vertices.push_back(v + Vec3{20, 0, 0});
  for (const auto& f : t.faces) m.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  const ValidationReport r = validate(m);
  EXPECT_EQ(r.components, 2u);
  const MeshProblem* p = find(r, "several_components");
  ASSERT_NE(p, nullptr);
  EXPECT_NE(p->message.find("2 separate components"), std::string::npos);
  EXPECT_FALSE(r.unfoldable());

  ValidateOptions keep;
  keep.keep_largest_component = true;
  const ValidationReport k = validate(m, keep);
  EXPECT_TRUE(k.unfoldable()) << k.reason();
  EXPECT_EQ(k.components, 1u);
  EXPECT_EQ(k.faces, 48u);
  EXPECT_EQ(k.genus, 1);
  EXPECT_EQ(k.largest_component.faces.size(), 48u);
  EXPECT_EQ(k.largest_component.vertices.size(), 24u);
  ASSERT_NE(find(k, "kept_largest_component"), nullptr);
  EXPECT_EQ(find(k, "kept_largest_component")->message,
            "kept the largest of 2 components (48 of 52 faces)");
}

TEST(Validate, TriangulatedIsANoteNotAProblem) {
  LoadedMesh loaded;
  loaded.mesh = tetrahedron();
  loaded.triangulated = true;
  const ValidationReport r = validate(loaded);
  EXPECT_TRUE(r.unfoldable());
  const MeshProblem* p = find(r, "triangulated");
  ASSERT_NE(p, nullptr);
  EXPECT_FALSE(p->blocking);
}

}  // namespace
}  // namespace papernet
