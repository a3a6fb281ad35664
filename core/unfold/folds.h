#pragma once

#include <vector>

#include "core/mesh/mesh.h"
#include "core/unfold/net.h"

namespace papernet {

/// What happens to the paper along one mesh edge of a net.
enum class EdgeKind {
  Cut,       ///< the two sides lie apart in the net: cut apart (boundary edges too)
  Mountain,  ///< glued, convex seen from the printed (outside) side: folds away from the viewer
  Valley,    ///< glued, concave seen from the printed side: folds towards the viewer
  Flat,      ///< glued, folds less than the flat threshold (may be left undrawn)
};

/// One side of a mesh edge in the net: the edge from net.points[face][k] to
/// net.points[face][(k + 1) % 3]; the face lies to its left (faces are counter-clockwise).
struct EdgeSide {
  int face = -1;
  int k = 0;
};

/// One undirected mesh edge, seen in the net.
struct NetEdge {
  EdgeKind kind = EdgeKind::Cut;
  EdgeSide a;          ///< always set
  EdgeSide b;          ///< the other face's side; b.face == -1 for a boundary edge
  double fold = 0;     ///< signed fold angle in radians: > 0 mountain (convex), < 0 valley
  int cut_index = -1;  ///< 0, 1, ... over interior cut edges (the label number minus one); else -1
};

struct FoldOptions {
  /// Glued edges whose fold angle is below this (degrees) are classified Flat.
  double flat_angle_deg = 1.0;
};

/// True when two sides of a mesh edge lie on each other in a net: side a0 -> a1 of one face and
/// side b0 -> b1 of the face across (which runs the other way) end at the same points, within
/// 1e-6 of the edge's length. The rule by which classify_edges calls an edge glued, not cut.
bool sides_coincide(Vec2 a0, Vec2 a1, Vec2 b0, Vec2 b1);

/// Every mesh edge of a net, classified. An edge is glued (a fold) exactly when its two sides
/// lie on each other in the net (same end points within 1e-6 of its length, faces on opposite
/// sides): a tree link, or two faces that happen to meet there without a tree link; such an
/// edge stays joined in the print and needs no tab or label. Every other interior edge is cut;
/// cut edges are numbered in order of appearance.
/// \pre mesh is manifold (each edge in at most two faces) and net belongs to it.
/// \throw TopologyException when an edge has more than two faces.
std::vector<NetEdge> classify_edges(const Mesh& mesh, const Net& net,
                                    const FoldOptions& options = {});

/// Signed fold angle (radians) across the edge shared by faces f and g: the angle between their
/// normals, positive when the edge is convex (mountain seen from outside), negative when concave.
double fold_angle(const Mesh& mesh, int f, int g);

}  // namespace papernet
