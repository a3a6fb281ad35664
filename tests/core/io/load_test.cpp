// Loading: every format from bytes written here, the bundled meshes, glTF transforms, buffers
// and modes, and the limits that refuse lying headers before allocating.
#include "core/io/load.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>

#include "core/errors.h"
#include "tests/support/hostile_bytes.h"
#include "tests/support/paths.h"

namespace papernet {
namespace {

using test::draco_header;
using test::varint;

const std::string kData = papernet::test::test_data_dir();

// A tetrahedron, faces counter-clockwise from outside.
const double kTetra[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const int kTetraFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

std::string binary_stl() {
  std::string s(80, ' ');
  s.replace(0, 5, "solid");  // binary STLs often start with this word too
  const std::uint32_t n = 4;
  s.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& f : kTetraFaces) {
    float rec[12] = {};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) rec[3 + 3 * k + c] = float(kTetra[f[k]][c]);
    s.append(reinterpret_cast<const char*>(rec), 48);
    s.append(2, '\0');
  }
  return s;
}

std::string ascii_stl() {
  std::string s = "solid tetra\n";
  for (const auto& f : kTetraFaces) {
    s += "facet normal 0 0 0\n outer loop\n";
    for (int k = 0; k < 3; ++k)
      s += "  vertex " + std::to_string(kTetra[f[k]][0]) + " " + std::to_string(kTetra[f[k]][1]) +
           " " + std::to_string(kTetra[f[k]][2]) + "\n";
    s += " endloop\nendfacet\n";
  }
  return s + "endsolid tetra\n";
}

std::string ply_header(const std::string& format) {
  return "ply\nformat " + format +
         " 1.0\ncomment made by a test\nelement vertex 4\nproperty float x\nproperty float "
         "y\nproperty float z\nproperty uchar red\nelement face 4\nproperty list uchar int "
         "vertex_indices\nend_header\n";
}

std::string ascii_ply() {
  std::string s = ply_header("ascii");
  for (const auto& v : kTetra)
    s += std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + " 7\n";
  for (const auto& f : kTetraFaces)
    s += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
         "\n";
  return s;
}

template <typename T>
void put(std::string& s, T value, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

std::string binary_ply(bool big) {
  std::string s = ply_header(big ? "binary_big_endian" : "binary_little_endian");
  for (const auto& v : kTetra) {
    for (double c : v) put(s, float(c), big);
    put(s, std::uint8_t{7}, big);
  }
  for (const auto& f : kTetraFaces) {
    put(s, std::uint8_t{3}, big);
    for (int i : f) put(s, std::int32_t(i), big);
  }
  return s;
}

std::string tetra_obj() {
  std::string s = "# tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  for (const auto& f : kTetraFaces)
    s += "f " + std::to_string(f[0] + 1) + "/1/1 " + std::to_string(f[1] + 1) + "//2 " +
         std::to_string(f[2] + 1) + "\n";
  return s;
}

std::string tetra_off() {
  std::string s = "OFF # a comment\n4 4 6\n";
  for (const auto& v : kTetra)
    s += std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
  for (const auto& f : kTetraFaces)
    s += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
         " 1.0 0.0 0.0\n";  // a face colour, as COFF-style files carry
  return s;
}

void expect_tetra(const LoadedMesh& m) {
  ASSERT_EQ(m.mesh.vertices.size(), 4u);
  ASSERT_EQ(m.mesh.faces.size(), 4u);
  for (int f = 0; f < 4; ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = m.mesh.vertices[m.mesh.faces[f][k]];
      const auto& want = kTetra[kTetraFaces[f][k]];
      EXPECT_EQ(p.x, want[0]);
      EXPECT_EQ(p.y, want[1]);
      EXPECT_EQ(p.z, want[2]);
    }
}

struct Case {
  const char* name;
  std::string (*make)();
  MeshFormat format;
};

TEST(Load, EveryTextAndBinaryFormatReadsTheSameTetrahedron) {
  const Case cases[] = {
      {"obj", tetra_obj, MeshFormat::Obj},
      {"off", tetra_off, MeshFormat::Off},
      {"ascii ply", ascii_ply, MeshFormat::Ply},
      {"binary little-endian ply", [] { return binary_ply(false); }, MeshFormat::Ply},
      {"binary big-endian ply", [] { return binary_ply(true); }, MeshFormat::Ply},
      {"ascii stl", ascii_stl, MeshFormat::Stl},
      {"binary stl", binary_stl, MeshFormat::Stl},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string bytes = c.make();
    EXPECT_EQ(sniff_format(bytes), c.format);
    const LoadedMesh given = load_mesh(bytes, c.format);
    EXPECT_EQ(given.format, c.format);
    expect_tetra(given);
    const LoadedMesh sniffed = load_mesh(bytes, MeshFormat::Unknown);
    EXPECT_EQ(sniffed.format, c.format);
    expect_tetra(sniffed);
  }
}

TEST(Load, StlCornersAreWeldedIntoSharedVertices) {
  const LoadedMesh m = load_mesh(binary_stl(), MeshFormat::Stl);
  EXPECT_EQ(m.raw_vertices, 12u);
  EXPECT_EQ(m.mesh.vertices.size(), 4u);
  EXPECT_FALSE(m.triangulated);
}

TEST(Load, WeldingMergesMinusZeroAndKeepsNaNsApart) {
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -0 -0 -0\nv 0 1 0\nv 0 0 1\n"
      "v nan 0 0\nv nan 0 0\nf 1 2 3\nf 4 5 6\nf 1 7 8\n";
  const LoadedMesh m = load_mesh(obj, MeshFormat::Obj);
  EXPECT_EQ(m.mesh.vertices.size(), 6u);  // 4 finite positions + 2 NaN vertices never merged
  EXPECT_EQ(m.mesh.faces[1][0], 0);
}

TEST(Load, ObjNegativeIndicesContinuationsAndSkippedElements) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 \\\n -2 -1\nl 1 2\nf 1 2\n";
  const LoadedMesh m = load_mesh(obj, MeshFormat::Obj);
  EXPECT_EQ(m.mesh.faces.size(), 2u);
  EXPECT_TRUE(m.triangulated);
  std::string notes;
  for (const auto& n : m.notes) notes += n + ";";
  EXPECT_NE(notes.find("1 line elements were skipped"), std::string::npos) << notes;
  EXPECT_NE(notes.find("fewer than 3 vertices"), std::string::npos) << notes;
}

TEST(Load, OffWithCountsGluedToTheKeyword) {
  const std::string off = "OFF4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  const LoadedMesh m = load_mesh(off, MeshFormat::Unknown);
  EXPECT_EQ(m.format, MeshFormat::Off);
  EXPECT_EQ(m.mesh.faces.size(), 2u);
  EXPECT_TRUE(m.triangulated);
}

TEST(Load, ObjQuadIsTriangulatedAndWelded) {
  // Two quads sharing an edge, written with duplicated vertices: welding must merge them.
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "v 1 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\n"
      "f 1 2 3 4\nf 5 6 7 8\n";
  const LoadedMesh loaded = load_mesh(obj, MeshFormat::Obj);
  EXPECT_EQ(loaded.mesh.faces.size(), 4u);
  EXPECT_EQ(loaded.mesh.vertices.size(), 6u);
  EXPECT_TRUE(loaded.triangulated);
}

TEST(Load, PlyTriangleStripsKeepOneOrientation) {
  // A unit square as the strip 0 1 3 2, then a restart and a strip with a join (repeated 2).
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement tristrips 1\nproperty list int int vertex_indices\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n9 0 1 2 -1 1 3 2 2 2\n";
  const LoadedMesh m = load_mesh(ply, MeshFormat::Ply);
  ASSERT_EQ(m.mesh.faces.size(), 2u);
  EXPECT_TRUE(m.triangulated);
  for (int f = 0; f < 2; ++f) EXPECT_GT(face_normal(m.mesh, f).z, 0) << f;
}

TEST(Load, MalformedTextNamesTheFault) {
  EXPECT_THROW(load_mesh("v 1 2\nf 1 2 3\n", MeshFormat::Obj), IOException);
  try {
    load_mesh("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", MeshFormat::Obj);
    FAIL() << "an out-of-range index must be refused";
  } catch (const IOException& e) {
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_mesh("", MeshFormat::Unknown), IOException);
  EXPECT_THROW(load_mesh("hello world\n", MeshFormat::Unknown), IOException);
}

// ---------------------------------------------------------------------------------------------
// Limits: lying headers are refused before anything is allocated for what they claim.

std::string message_of(const std::string& bytes, MeshFormat format, const LoadOptions& o = {}) {
  try {
    load_mesh(bytes, format, o);
  } catch (const IOException& e) {
    return e.what();
  }
  return "";
}

TEST(LoadLimits, BytesAndFaces) {
  LoadOptions small;
  small.max_bytes = 100;
  EXPECT_NE(message_of(ascii_stl(), MeshFormat::Stl, small).find("limit"), std::string::npos);
  LoadOptions few_vertices;
  few_vertices.max_vertices = 3;
  for (const auto& bytes : {tetra_obj(), tetra_off(), ascii_ply(), binary_stl(), ascii_stl()})
    EXPECT_NE(message_of(bytes, MeshFormat::Unknown, few_vertices).find("limit of 3"),
              std::string::npos);
  LoadOptions few;
  few.max_faces = 3;
  for (const auto& bytes : {tetra_obj(), tetra_off(), ascii_ply(), binary_ply(false), binary_stl()})
    EXPECT_NE(message_of(bytes, MeshFormat::Unknown, few).find("limit"), std::string::npos);
}

TEST(LoadLimits, HeadersClaimingMoreThanTheFileHolds) {
  std::string stl = binary_stl();
  const std::uint32_t huge = 0x7fffffff;
  std::memcpy(stl.data() + 80, &huge, 4);
  EXPECT_NE(message_of(stl, MeshFormat::Stl).find("declares 2147483647 triangles"),
            std::string::npos);
  std::string ply = binary_ply(false);
  ply.replace(ply.find("vertex 4"), 8, "vertex 4000000000");
  EXPECT_NE(message_of(ply, MeshFormat::Ply).find("declares 4000000000"), std::string::npos);
  std::string off = tetra_off();
  off.replace(off.find("4 4 6"), 5, "900000000 4 6");
  EXPECT_NE(message_of(off, MeshFormat::Off).find("declares 900000000"), std::string::npos);
}

// Regressions (docs/reliability.md): the vertex limit was checked per "vertex" element, so a PLY
// declaring the element twice read twice the limit; a face list was sized from its declared
// length checked against bytes rather than values (8 bytes of index per byte of file).
TEST(LoadLimits, PlyRepeatedVertexElementsAndLongListsAreBounded) {
  std::string twice = binary_ply(false);
  const std::string vertex_element =
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar "
      "red\n";
  twice.insert(twice.find("element face"), vertex_element);
  const std::size_t body = twice.find("end_header\n") + 11;
  twice.insert(body, twice.substr(body, 4 * 13));  // the second element's four vertices
  LoadOptions six;
  six.max_vertices = 6;
  EXPECT_NE(message_of(twice, MeshFormat::Ply, six).find("limit of 6"), std::string::npos);
  std::string long_list = binary_ply(false);
  long_list[long_list.find("end_header\n") + 11 + 4 * 13] = 40;  // 40 ints, 51 bytes left
  EXPECT_NE(message_of(long_list, MeshFormat::Ply).find("bad list length"), std::string::npos)
      << message_of(long_list, MeshFormat::Ply);
}

TEST(LoadLimits, DracoCountsAreCheckedBeforeDecoding) {
  // Edgebreaker: traversal type, vertices, faces, attribute data, symbols, split symbols.
  const std::string edgebreaker = draco_header(1, 1) + '\0' + varint(3) + varint(1u << 30) + '\0' +
                                  varint(1) + varint(0) + std::string(16, '\0');
  EXPECT_NE(message_of(edgebreaker, MeshFormat::Draco).find("declares 1073741824 faces"),
            std::string::npos);
  const std::string sequential =
      draco_header(1, 0) + varint(1) + varint(0xfffffff0u) + std::string(16, '\0');
  EXPECT_NE(message_of(sequential, MeshFormat::Unknown).find("points for 1 faces"),
            std::string::npos);
  EXPECT_NE(
      message_of(draco_header(0, 0) + std::string(8, '\0'), MeshFormat::Draco).find("point cloud"),
      std::string::npos);
  // Metadata whose entry claims 4 GB: draco itself would allocate it.
  std::string meta = draco_header(1, 1);
  meta[10] = char(0x80);  // flags high byte: metadata present
  meta += varint(0) + varint(1) + char(1) + "k" + varint(0xffffffffu) + "x";
  EXPECT_NE(message_of(meta, MeshFormat::Draco).find("ends inside metadata entry"),
            std::string::npos);
  EXPECT_NE(message_of("DRACO\2", MeshFormat::Draco).find("ends inside"), std::string::npos);
}

// Found by fuzz_draco in the CI's smoke run (docs/reliability.md, row 9): refused before any
// conversion. The glTF route (a Draco primitive naming such an attribute) is in
// load_gltf_test.cpp.
TEST(LoadLimits, DracoPositionsMustBeNumbers) {
  const std::string message = message_of(test::bool_positions_drc(), MeshFormat::Draco);
  EXPECT_NE(message.find("positions have data type 11, not a number type"), std::string::npos)
      << message;
}

// ---------------------------------------------------------------------------------------------
// The bundled meshes (counts from ../shared/data/meshes/STATS.tsv, see tests/data/LICENSES.md).

TEST(LoadFiles, BundledMeshesLoadWithTheirWeldedCounts) {
  struct Expect {
    const char* file;
    MeshFormat format;
    std::size_t vertices, faces;
  };
  const Expect files[] = {
      {"sample.obj", MeshFormat::Obj, 502, 1000},
      {"reference.obj", MeshFormat::Obj, 845, 1610},
      {"thingi10k_134617.stl", MeshFormat::Stl, 217, 428},
      {"thingi10k_65004.stl", MeshFormat::Stl, 731, 1466},
      {"mirror.ply", MeshFormat::Ply, 143, 286},
      {"testplate.glb", MeshFormat::Glb, 130, 264},
      {"Duck.glb", MeshFormat::Glb, 2108, 4212},
      {"Box_Draco.glb", MeshFormat::Glb, 8, 12},
  };
  for (const Expect& e : files) {
    SCOPED_TRACE(e.file);
    const LoadedMesh m = load_mesh_file(kData + "/" + e.file);
    EXPECT_EQ(m.format, e.format);
    EXPECT_EQ(m.mesh.vertices.size(), e.vertices);
    EXPECT_EQ(m.mesh.faces.size(), e.faces);
  }
  // glTF splits vertices at seams; welding is what makes these closed surfaces.
  EXPECT_EQ(load_mesh_file(kData + "/testplate.glb").raw_vertices, 398u);
  EXPECT_EQ(load_mesh_file(kData + "/Box_Draco.glb").raw_vertices, 24u);
}

TEST(LoadFiles, DuckNodeMatrixIsApplied) {
  // The Duck's root node scales by 0.01: its welded positions are within about 2 units.
  const LoadedMesh m = load_mesh_file(kData + "/Duck.glb");
  EXPECT_NEAR(bounding_box_diagonal(m.mesh), 2.4, 0.6);
}

TEST(LoadFiles, MissingFileIsAnIOException) {
  EXPECT_THROW(load_mesh_file(kData + "/no_such_file.obj"), IOException);
}

}  // namespace
}  // namespace papernet
