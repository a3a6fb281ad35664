#pragma once

#include <algorithm>
#include <array>

#include "core/vec.h"

namespace papernet {

using Triangle2 = std::array<Vec2, 3>;

/// The overlap tolerance of papernet's nets, relative to the mesh's bounding-box diagonal: two
/// faces whose interiors intersect by less do not overlap (the unfolder's; the net checker
/// ignores twice this). Input in float rounds at about 1e-8 of the diagonal, so the slivers of
/// CAD plates overlap their neighbours by that much whatever the tree.
inline constexpr double kOverlapTolerance = 5e-8;

/// The finer tolerance of the pass that changes a net's cuts for glue tabs (core/tabs) and of
/// leaf_room: a move it makes is overlap-free by this much, so its nets pass the same check with
/// margin. With kOverlapTolerance itself the pass's search takes other paths, and printed more
/// sheets on 15 of the 30 benchmark nets it changed, fewer on 3 (docs/tabs.md).
inline constexpr double kTabRoomOverlapTolerance = 1e-9;  // a fiftieth of kOverlapTolerance

inline Box2 triangle_box(const Triangle2& t) {
  return {{std::min({t[0].x, t[1].x, t[2].x}), std::min({t[0].y, t[1].y, t[2].y})},
          {std::max({t[0].x, t[1].x, t[2].x}), std::max({t[0].y, t[1].y, t[2].y})}};
}

/// False when boxes `a` and `b` are apart or overlap by at most `tolerance` along an axis: then
/// triangles_overlap is false for any triangles with these boxes (its own first test).
inline bool boxes_overlap(const Box2& a, const Box2& b, double tolerance) {
  return !(a.hi.x <= b.lo.x + tolerance || b.hi.x <= a.lo.x + tolerance ||
           a.hi.y <= b.lo.y + tolerance || b.hi.y <= a.lo.y + tolerance);
}

/// True when the interiors of the counter-clockwise triangles a and b intersect by more than
/// `tolerance` (a length: kOverlapTolerance times the mesh's bounding-box diagonal). Triangles that
/// touch along an edge or at a vertex, or whose shared corners differ by rounding, do not overlap.
/// Exact for glued neighbours: a shared edge copied bit for bit separates them even with tolerance
/// 0. Uses separating axes along the six edges, which is exact for convex polygons in the plane.
bool triangles_overlap(const Triangle2& a, const Triangle2& b, double tolerance);

/// triangles_overlap without its first test: the same answer for triangles whose boxes overlap
/// (boxes_overlap of their triangle_box is true), for callers that keep face boxes and test them
/// first (for other triangles its answer may be wrong).
bool triangles_overlap_in_boxes(const Triangle2& a, const Triangle2& b, double tolerance);

}  // namespace papernet
