#pragma once

#include <cstddef>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/tabs/tab_clearance.h"
#include "core/unfold/net.h"

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
  std::size_t interior_vertices = 0;  ///< the others in a face
  std::size_t leaf_room_vertices = 0;  ///< interior vertices where a leaf can have room (leaf_room)
  std::size_t leaves_without_room = 0;          ///< leaves at the other vertices
  std::size_t leaves_without_room_blocked = 0;  ///< ... whose edge is blocked (all of them)
  std::size_t branch_vertices = 0;              ///< vertices with three or more cut edges
  /// Leaves whose edge is blocked, and all leaves, by defect in whole degrees (0..179, the
  /// last bucket also takes larger and negative defects are counted by their size).
  std::vector<std::size_t> blocked_leaf_defects, leaf_defects;
};

/// Describes where `net`'s cut edges lack room for a tab of `options.min_height`; a vertex is
/// flat when the size of its angle defect is below `flat_defect` (radians).
/// `blocked`, when given, are net's cut edges without room, as the pass that made the net found
/// them (TabClearanceResult::blocked): not looked for again.
TabRoomReport describe_tab_room(const Mesh& mesh, const Net& net,
                                const TabClearanceOptions& options, double flat_defect,
                                const std::vector<EdgeSide>* blocked = nullptr);

/// Interior vertices where a leaf of the cut tree can have room for a tab: with the faces around
/// v laid out flat as one fan, opened at one of v's edges (a leaf's only cut edge), a tab of
/// `options.min_height` (half the edge on shorter edges; any of tab_shapes) fits on one of that
/// edge's two sides without overlapping the fan. The fan's two copies of the edge meet at v at
/// its angle defect, so this fails at nearly flat vertices: a leaf there always lacks room,
/// whatever the rest of the net. Necessary, not sufficient (other faces may crowd the edge).
/// Never at vertices with a defect <= 0 (their fan overlaps itself: no overlap-free net has a
/// leaf there), on the boundary or in no face.
std::vector<char> leaf_room(const Mesh& mesh, const TabClearanceOptions& options);

}  // namespace papernet
