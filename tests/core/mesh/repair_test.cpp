// Mesh repair (core/mesh/repair.h): each defect a real model has, repaired and reported, and the
// result a mesh the validator accepts (one piece per part).
#include "core/mesh/repair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/io/load.h"
#include "core/mesh/validate.h"
#include "tests/support/meshes.h"
#include "tests/support/paths.h"

namespace papernet::test {
namespace {

const MeshRepair* find(const RepairResult& r, const std::string& code) {
  for (const MeshRepair& m : r.repairs)
    if (m.code == code) return &m;
  return nullptr;
}

// The faces as their corners' positions, rotated to start at the smallest: the same surface
// whatever the vertex numbering.
std::vector<std::array<std::array<double, 3>, 3>> surface(const Mesh& m) {
  std::vector<std::array<std::array<double, 3>, 3>> out;
  for (const auto& f : m.faces) {
    std::array<std::array<double, 3>, 3> t;
    for (int c = 0; c < 3; ++c) {
      const Vec3 p = m.vertices[f[c]];
      t[c] = {p.x, p.y, p.z};
    }
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.push_back(t);
  }
  return out;
}

std::string codes(const RepairResult& r) {
  std::string s;
  for (const MeshRepair& m : r.repairs) s += m.code + " " + std::to_string(m.count) + "; ";
  return s;
}

// Every blocking problem the validator finds, "" when the mesh can be unfolded as pieces.
std::string blocking(const Mesh& mesh) {
  std::string s;
  for (const MeshProblem& p : validate(mesh).problems)
    if (p.blocking && p.code != "several_components") s += p.code + ": " + p.message + "; ";
  return s;
}

LoadedMesh obj(const std::string& text) { return load_mesh(text, MeshFormat::Obj); }

// Two tetrahedra; `shared` joins them at one vertex index (a pinch in the file), else each has
// its own vertex at the same place (a manifold file: two parts touching).
std::string two_tetrahedra(bool shared) {
  std::string s = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv -1 0 0\nv 0 -1 0\nv 0 0 -1\n";
  if (!shared) s += "v 0 0 0\n";
  const std::string apex = shared ? "1" : "8";
  s += "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
  s += "f " + apex + " 5 6\nf " + apex + " 6 7\nf 5 7 6\nf " + apex + " 7 5\n";
  return s;
}

TEST(Repair, APinchInTheFileIsSplitAndReported) {
  const LoadedMesh in = obj(two_tetrahedra(true));
  ASSERT_FALSE(validate(in.mesh).unfoldable());
  const RepairResult r = repair_mesh(in.mesh, in.raw_faces);
  const MeshRepair* split = find(r, "split_pinched_vertices");
  ASSERT_NE(split, nullptr) << codes(r);
  EXPECT_EQ(split->count, 1u);
  EXPECT_EQ(split->elements, std::vector<int>{0});
  EXPECT_NE(split->message.find("(0, 0, 0)"), std::string::npos) << split->message;
  EXPECT_EQ(r.repairs.size(), 1u) << codes(r);
  EXPECT_EQ(r.mesh.vertices.size(), 8u);
  EXPECT_EQ(blocking(r.mesh), "");
  const std::vector<Mesh> parts = split_components(r.mesh);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].faces.size(), 4u);
  EXPECT_EQ(parts[1].faces.size(), 4u);
}

// The file keeps the two fans apart; only the loader's weld by position joined them. Undoing
// that is no repair: nothing is reported, and no pinch is made.
TEST(Repair, CoincidentVerticesOnSeparateFansAreNotAPinch) {
  const LoadedMesh in = obj(two_tetrahedra(false));
  ASSERT_FALSE(validate(in.mesh).unfoldable()) << "the weld by position made a pinch";
  const RepairResult r = repair_mesh(in.mesh, in.raw_faces);
  EXPECT_TRUE(r.repairs.empty()) << codes(r);
  EXPECT_EQ(r.mesh.vertices.size(), 8u);
  EXPECT_EQ(blocking(r.mesh), "");
  EXPECT_EQ(split_components(r.mesh).size(), 2u);
  // Without the file's vertices to tell (a soup), the same pinch is reported.
  EXPECT_NE(find(repair_mesh(in.mesh), "split_pinched_vertices"), nullptr);
}

TEST(Repair, AnEdgeOfThreeFacesIsCut) {
  // A tetrahedron with a fin: a third face on edge 1-2.
  const LoadedMesh in =
      obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0.5 -1 0.5\n"
          "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 1 2 5\n");
  const RepairResult r = repair_mesh(in.mesh, in.raw_faces);
  const MeshRepair* cut = find(r, "cut_non_manifold_edges");
  ASSERT_NE(cut, nullptr) << codes(r);
  EXPECT_EQ(cut->count, 1u);
  EXPECT_EQ(cut->elements, (std::vector<int>{0, 1}));
  EXPECT_EQ(r.mesh.faces.size(), 5u);
  EXPECT_EQ(blocking(r.mesh), "");
  // The tetrahedron keeps its edge; the fin comes off as a part of its own.
  const std::vector<Mesh> parts = split_components(r.mesh);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].faces.size(), 4u);
  EXPECT_EQ(validate(parts[0]).boundary_loops, 0u);
  EXPECT_EQ(parts[1].faces.size(), 1u);
}

// The same fin listed first: the file's order pairs it with a face of the tetrahedron, whose
// cut side stays joined at both ends through the faces around them. That face is detached at one
// end, so no edge keeps three faces.
TEST(Repair, AFinPairedFirstStillLeavesNoEdgeOfThreeFaces) {
  const LoadedMesh in =
      obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0.5 -1 0.5\n"
          "f 1 2 5\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n");
  const RepairResult r = repair_mesh(in.mesh, in.raw_faces);
  ASSERT_NE(find(r, "cut_non_manifold_edges"), nullptr) << codes(r);
  EXPECT_EQ(r.mesh.faces.size(), 5u);
  EXPECT_EQ(blocking(r.mesh), "") << codes(r);
}

// A face and its reverse folded flat on an edge of a closed surface (Suzanne's eyebrow in the
// classic collection has one): both go, and the tetrahedron is left as it was, closed.
TEST(Repair, AFlapOfAFaceAndItsReverseGoesWhole) {
  const LoadedMesh in =
      obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0.5 -1 0.5\n"
          "f 1 3 2\nf 1 2 4\nf 1 2 5\nf 1 5 2\nf 2 3 4\nf 3 1 4\n");
  ASSERT_FALSE(validate(in.mesh).unfoldable());
  const RepairResult r = repair_mesh(in.mesh, in.raw_faces);
  const MeshRepair* dup = find(r, "removed_duplicate_faces");
  ASSERT_NE(dup, nullptr) << codes(r);
  EXPECT_EQ(dup->count, 2u);
  EXPECT_EQ(dup->elements, (std::vector<int>{2, 3}));
  EXPECT_EQ(r.repairs.size(), 1u) << codes(r);
  EXPECT_EQ(r.mesh.faces.size(), 4u);
  EXPECT_EQ(blocking(r.mesh), "");
  EXPECT_EQ(validate(r.mesh).boundary_loops, 0u);
}

// Found by fuzz_stl: a cluster of faces with coordinates near 1e-41, where a flip made another
// zero-area face. Whatever repair leaves, the validator accepts.
TEST(Repair, ZeroAreaFacesLeftByFlipsInAClusterGoToo) {
  const LoadedMesh in =
      load_mesh_file(papernet::test::test_data_dir() + "/fuzz/stl_degenerate_cluster.stl");
  const RepairResult r = repair_mesh(in.mesh, in.raw_faces);
  ASSERT_NE(find(r, "removed_degenerate_faces"), nullptr) << codes(r);
  EXPECT_EQ(blocking(r.mesh), "") << codes(r);
}

// A T-junction closed by a zero-area face (a cap: vertex 5 on edge 1-3) is flipped away with
// its neighbour: the square stays closed, with no degenerate face.
TEST(Repair, ACapIsFlippedAwayWithoutAHole) {
  const LoadedMesh in =
      obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0\n"
          "f 1 2 5\nf 5 2 3\nf 1 3 4\nf 1 5 3\n");
  ASSERT_FALSE(validate(in.mesh).unfoldable());
  const RepairResult r = repair_mesh(in.mesh, in.raw_faces);
  const MeshRepair* removed = find(r, "removed_degenerate_faces");
  ASSERT_NE(removed, nullptr) << codes(r);
  EXPECT_EQ(removed->count, 1u);
  EXPECT_EQ(removed->elements, std::vector<int>{3});
  EXPECT_EQ(blocking(r.mesh), "");
  EXPECT_EQ(r.mesh.faces.size(), 4u);
  const ValidationReport v = validate(r.mesh);
  EXPECT_EQ(v.boundary_loops, 1u);  // one square: no slit
  double area = 0;
  for (std::size_t f = 0; f < r.mesh.faces.size(); ++f) area += face_area(r.mesh, int(f));
  EXPECT_NEAR(area, 1.0, 1e-12);
}

// A needle (two corners 1e-13 apart) is collapsed along its shortest edge.
TEST(Repair, ANeedleIsCollapsed) {
  const LoadedMesh in =
      obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.0000000000001 1 0\nv -1 0 0\nv 0 -1 0\n"
          "f 1 2 3\nf 1 3 4\nf 1 4 5\nf 1 5 6\nf 1 6 2\n");
  const RepairResult r = repair_mesh(in.mesh, in.raw_faces);
  const MeshRepair* removed = find(r, "removed_degenerate_faces");
  ASSERT_NE(removed, nullptr) << codes(r);
  EXPECT_EQ(removed->count, 1u);
  EXPECT_EQ(r.mesh.faces.size(), 4u);
  EXPECT_EQ(r.mesh.vertices.size(), 5u);
  EXPECT_EQ(blocking(r.mesh), "");
  EXPECT_EQ(validate(r.mesh).boundary_loops, 1u);
}

TEST(Repair, FlippedFacesTurnBackAndAnInsideOutPartTurnsOutwards) {
  Mesh one = cube();
  std::swap(one.faces[5][1], one.faces[5][2]);
  RepairResult r = repair_mesh(one);
  const MeshRepair* turned = find(r, "reoriented_faces");
  ASSERT_NE(turned, nullptr) << codes(r);
  EXPECT_EQ(turned->count, 1u);
  EXPECT_EQ(turned->elements, std::vector<int>{5});
  EXPECT_EQ(blocking(r.mesh), "");
  EXPECT_EQ(surface(r.mesh), surface(cube()));

  Mesh inside_out = cube();
  for (auto& f : inside_out.faces) std::swap(f[1], f[2]);
  r = repair_mesh(inside_out);
  turned = find(r, "reoriented_faces");
  ASSERT_NE(turned, nullptr) << codes(r);
  EXPECT_EQ(turned->count, 12u);
  EXPECT_NE(turned->message.find("outwards"), std::string::npos);
  EXPECT_EQ(surface(r.mesh), surface(cube()));
  EXPECT_TRUE(repair_mesh(cube()).repairs.empty());
}

TEST(Repair, DuplicateFacesGoOnceEitherWayRound) {
  Mesh m = cube();
  m.faces.push_back(m.faces[2]);
  m.faces.push_back({m.faces[3][0], m.faces[3][2], m.faces[3][1]});
  const RepairResult r = repair_mesh(m);
  const MeshRepair* dup = find(r, "removed_duplicate_faces");
  ASSERT_NE(dup, nullptr) << codes(r);
  EXPECT_EQ(dup->count, 2u);
  EXPECT_EQ(r.mesh.faces.size(), 12u);
  EXPECT_EQ(blocking(r.mesh), "");
}

// A Moebius strip cannot be oriented: one edge is cut, and the strip becomes an oriented band.
TEST(Repair, AMoebiusStripIsCutWhereItCannotBeOriented) {
  Mesh strip;
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n, t = a / 2;
    for (double s : {-0.3, 0.3})
      strip.vertices.push_back({(1 + s * std::cos(t)) * std::cos(a),
                                (1 + s * std::cos(t)) * std::sin(a), s * std::sin(t)});
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 1;
    // The last quad joins the first with its two rails swapped: the half twist.
    const int c = i + 1 < n ? 2 * (i + 1) : 1, d = i + 1 < n ? 2 * (i + 1) + 1 : 0;
    strip.faces.push_back({a, c, b});
    strip.faces.push_back({b, c, d});
  }
  ASSERT_FALSE(validate(strip).unfoldable());
  const RepairResult r = repair_mesh(strip);
  ASSERT_NE(find(r, "cut_non_orientable_edges"), nullptr) << codes(r);
  EXPECT_EQ(blocking(r.mesh), "");
  EXPECT_EQ(r.mesh.faces.size(), strip.faces.size());
}

TEST(Repair, PartsComeLargestFirstWithTheirOwnVertices) {
  Mesh m = tetrahedron();
  const Mesh big = cube();
  for (const auto& f : big.faces) m.faces.push_back({f[0] + 4, f[1] + 4, f[2] + 4});
  m.vertices.insert(m.vertices.end(), big.vertices.begin(), big.vertices.end());
  const std::vector<Mesh> parts = split_components(m);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(surface(parts[0]), surface(big));
  EXPECT_EQ(parts[0].vertices.size(), 8u);
  EXPECT_EQ(surface(parts[1]), surface(tetrahedron()));
}

}  // namespace
}  // namespace papernet::test
