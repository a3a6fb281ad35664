#pragma once

#include <vector>

#include "core/mesh/mesh.h"
#include "core/unfold/net.h"
#include "core/vec.h"

namespace papernet {

/// A minimum-area oriented bounding box. Rotating a point p by `angle` (radians,
/// counter-clockwise) about the origin puts it into the axis-aligned box [lo, hi]; the box's
/// long side lies along x (width >= height).
struct OrientedBox {
  double angle = 0;
  Vec2 lo, hi;
  double width() const { return hi.x - lo.x; }
  double height() const { return hi.y - lo.y; }
  double area() const { return width() * height(); }
};

/// Rotates p counter-clockwise by `angle` radians about the origin.
Vec2 rotate(Vec2 p, double angle);

/// Convex hull of the points, counter-clockwise, without collinear points (Andrew's chain).
std::vector<Vec2> convex_hull(std::vector<Vec2> points);

/// Minimum-area oriented bounding box of the points (convex hull + rotating calipers: the
/// optimal box has a side on a hull edge). Empty input gives an empty box at the origin.
OrientedBox min_area_box(const std::vector<Vec2>& points);

/// Figures describing how well a net uses its paper (the net JSON's coverage and aspect ratio).
struct NetBoxMetrics {
  int faces = 0;
  double face_area = 0;     ///< summed area of the mesh's faces (mesh units squared)
  double coverage = 0;      ///< face_area / area of the minimum-area box (0 when degenerate)
  double aspect_ratio = 1;  ///< long / short side of that box, >= 1 (1 when degenerate)
  OrientedBox box;          ///< the box and the rotation that puts the net into it
};

/// Coverage, aspect ratio and the minimum-area box of a net of `mesh`.
/// \pre net.points.size() == mesh.faces.size()
NetBoxMetrics net_metrics(const Mesh& mesh, const Net& net);

}  // namespace papernet
