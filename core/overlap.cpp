#include "core/overlap.h"

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

// Largest number of cells a face may cover in its level.
constexpr double kMaxCells = 16;

}  // namespace

bool triangles_overlap(const Triangle2& a, const Triangle2& b, double tolerance) {
  const Box2 ba = triangle_box(a), bb = triangle_box(b);
  if (ba.hi.x <= bb.lo.x + tolerance || bb.hi.x <= ba.lo.x + tolerance ||
      ba.hi.y <= bb.lo.y + tolerance || bb.hi.y <= ba.lo.y + tolerance)
    return false;
  for (int k = 0; k < 3; ++k) {
    if (separates(a[k], a[(k + 1) % 3], b, tolerance)) return false;
    if (separates(b[k], b[(k + 1) % 3], a, tolerance)) return false;
  }
  return true;
}

void OverlapGrid::reset(double cell_size) {
  double inv = 1.0 / cell_size;
  for (Level& l : levels_) {
    l.inv_cell = inv;
    l.buckets.clear();
    l.mask = 0;
    l.members.clear();
    inv *= 0.25;
  }
  range_.clear();
}

void OverlapGrid::place(int f) {
  const Range& r = range_[f];
  Level& l = levels_[r.level];
  for (int x = r.x0; x <= r.x1; ++x)
    for (int y = r.y0; y <= r.y1; ++y) l.buckets[bucket(l, x, y)].push_back(f);
}

void OverlapGrid::grow(Level& l) {
  l.buckets.assign(std::max<std::size_t>(64, 2 * l.buckets.size()), {});
  l.mask = l.buckets.size() - 1;
  for (int f : l.members) place(f);
}

void OverlapGrid::insert(int f, const Box2& box) {
  if (f >= static_cast<int>(range_.size())) range_.resize(f + 1);
  Range& r = range_[f];
  r.valid = true;
  r.level = kLevels;
  for (int i = 0; i < kLevels; ++i) {
    const Level& l = levels_[i];
    const int x0 = cell(l, box.lo.x), x1 = cell(l, box.hi.x), y0 = cell(l, box.lo.y),
              y1 = cell(l, box.hi.y);
    if (x1 < x0 || y1 < y0) break;  // not a number
    const double cells = (static_cast<double>(x1) - x0 + 1) * (static_cast<double>(y1) - y0 + 1);
    if (cells <= kMaxCells) {
      r.x0 = x0, r.x1 = x1, r.y0 = y0, r.y1 = y1, r.level = i;
      break;
    }
  }
  Level& l = levels_[r.level];
  r.slot = static_cast<int>(l.members.size());
  l.members.push_back(f);
  if (r.level == kLevels) return;
  if (4 * l.members.size() > l.buckets.size())
    grow(l);  // grow() places f too
  else
    place(f);
}

void OverlapGrid::remove(int f) {
  Range& r = range_[f];
  Level& l = levels_[r.level];
  range_[l.members.back()].slot = r.slot;
  l.members[r.slot] = l.members.back();
  l.members.pop_back();
  if (r.level < kLevels)
    for (int x = r.x0; x <= r.x1; ++x)
      for (int y = r.y0; y <= r.y1; ++y) {
        std::vector<int>& v = l.buckets[bucket(l, x, y)];
        const auto it = std::find(v.begin(), v.end(), f);
        *it = v.back();
        v.pop_back();
      }
  r.valid = false;
}

}  // namespace papernet
