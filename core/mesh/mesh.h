#pragma once

#include <array>
#include <vector>

#include "core/vec.h"

namespace papernet {

/// An indexed triangle mesh. Faces are counter-clockwise seen from outside (right-hand rule
/// gives the outward normal). This is the exchange type between all of papernet's algorithms;
/// algorithms that need connectivity build it themselves.
struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> faces;
};

/// Unnormalised normal of face f (twice its area in length).
Vec3 face_normal(const Mesh& mesh, int f);

/// Area of face f.
double face_area(const Mesh& mesh, int f);

/// The mesh's axis-aligned bounding box (Box3::empty() for a mesh without vertices).
Box3 bounding_box(const Mesh& mesh);

/// Length of the diagonal of the mesh's axis-aligned bounding box (0 for an empty mesh).
double bounding_box_diagonal(const Mesh& mesh);

/// The faces `faces` of `mesh`, in that order, as a mesh of their own: each face's corners in the
/// same order, the vertices they use renumbered in order of first use (a net of it is a net of
/// those faces).
Mesh mesh_of_faces(const Mesh& mesh, const std::vector<int>& faces);

/// Median length of the faces' edges, each edge counted once per face (0 for a mesh without
/// faces).
double median_edge_length(const Mesh& mesh);

}  // namespace papernet
