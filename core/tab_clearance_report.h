#pragma once

#include <cstddef>
#include <vector>

#include "core/mesh.h"
#include "core/net.h"
#include "core/tab_clearance.h"

namespace papernet {

/// Why the cut edges of a net lack room for a tab, in terms of the cut graph (the mesh's cut
/// edges as a graph on its vertices; a tree on a closed genus-0 mesh). A vertex is a *leaf*
/// when it is an interior vertex with exactly one cut edge: the two sides of that edge then
/// meet at it at its angle defect (2 pi minus its face angles), so a leaf at a nearly flat
/// vertex is a near-slit. A *hair* is a path of cut edges from a leaf through vertices with
/// two cut edges; along it the slit opens only by the accumulated defect.
struct TabRoomReport {
  std::size_t cut_edges = 0;
  std::size_t blocked = 0;            ///< cut edges without room (edges_without_tab_room)
  std::size_t blocked_leaf = 0;       ///< ... with an end that is a leaf
  std::size_t blocked_hair = 0;       ///< ... else on a hair (a path of two-cut vertices to a leaf)
  std::size_t blocked_other = 0;      ///< ... else (between branch vertices or on the boundary)
  std::size_t leaves = 0;             ///< leaves of the cut graph
  std::size_t flat_leaves = 0;        ///< ... whose defect is below `flat_defect`
  std::size_t sharp_vertices = 0;     ///< interior vertices with |defect| >= `flat_defect`
  std::size_t boundary_vertices = 0;  ///< vertices on the mesh's boundary (open meshes)
  std::size_t branch_vertices = 0;    ///< vertices with three or more cut edges
  /// Leaves whose edge is blocked, and all leaves, by defect in whole degrees (0..179, the
  /// last bucket also takes larger and negative defects are counted by their size).
  std::vector<std::size_t> blocked_leaf_defects, leaf_defects;
};

/// Describes where `net`'s cut edges lack room for a tab of `options.min_height`; a vertex is
/// flat when the size of its angle defect is below `flat_defect` (radians).
TabRoomReport describe_tab_room(const Mesh& mesh, const Net& net,
                                const TabClearanceOptions& options, double flat_defect);

/// Angle defect of every vertex: 2 pi minus the sum of its face angles; 0 for boundary vertices
/// and vertices in no face.
std::vector<double> angle_defects(const Mesh& mesh);

}  // namespace papernet
