#include "core/unfold/overlap.h"

namespace papernet {

namespace {

// True when every corner of `t` lies on the right of, or within `tolerance` of, the line through
// edge p->q (the outside of a counter-clockwise triangle with that edge).
bool separates(Vec2 p, Vec2 q, const Triangle2& t, double tolerance) {
  const Vec2 e = q - p;
  const double m = std::max({cross(e, t[0] - p), cross(e, t[1] - p), cross(e, t[2] - p)});
  if (m <= 0) return true;
  // cross = |e| * distance: compare without a square root.
  return m * m <= tolerance * tolerance * dot(e, e);
}

}  // namespace

bool triangles_overlap(const Triangle2& a, const Triangle2& b, double tolerance) {
  return boxes_overlap(triangle_box(a), triangle_box(b), tolerance) &&
         triangles_overlap_in_boxes(a, b, tolerance);
}

bool triangles_overlap_in_boxes(const Triangle2& a, const Triangle2& b, double tolerance) {
  for (int k = 0; k < 3; ++k) {
    if (separates(a[k], a[(k + 1) % 3], b, tolerance)) return false;
    if (separates(b[k], b[(k + 1) % 3], a, tolerance)) return false;
  }
  return true;
}

}  // namespace papernet
