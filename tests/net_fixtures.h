#pragma once

// Small meshes and a plain breadth-first unfolder for the output tests. The unfolder is
// deliberately simple (no overlap removal): the print writers must cope with any valid net.
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/net.h"

namespace papernet::testing {

Mesh tetrahedron();
Mesh cube();                        ///< unit cube, 12 triangles, outward CCW
Mesh octahedron(double top_z = 1);  ///< top vertex at (0, 0, top_z); below 0 it is dented

/// A net of `mesh` by breadth-first search over faces from face 0: every child is laid out
/// across the edge it shares with its parent from the 3D edge lengths.
Net bfs_net(const Mesh& mesh);

/// Every mesh file of tests/data (all formats the loader reads), by file name.
std::vector<std::pair<std::string, Mesh>> test_data_meshes();

}  // namespace papernet::testing
