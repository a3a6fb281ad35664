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

// Largest number of cells a face may cover before it goes to the list of big faces.
constexpr int kMaxCells = 64;

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
  inv_cell_ = 1.0 / cell_size;
  buckets_.assign(1024, {});
  mask_ = buckets_.size() - 1;
  count_ = 0;
  range_.clear();
  big_.clear();
}

void OverlapGrid::place(int f) {
  const Range& r = range_[f];
  for (int x = r.x0; x <= r.x1; ++x)
    for (int y = r.y0; y <= r.y1; ++y) buckets_[bucket(x, y)].push_back(f);
}

void OverlapGrid::grow() {
  buckets_.assign(2 * buckets_.size(), {});
  mask_ = buckets_.size() - 1;
  for (std::size_t f = 0; f < range_.size(); ++f)
    if (range_[f].valid && !range_[f].big) place(static_cast<int>(f));
}

void OverlapGrid::insert(int f, const Box2& box) {
  if (f >= static_cast<int>(range_.size())) range_.resize(f + 1);
  Range& r = range_[f];
  r = {cell(box.lo.x), cell(box.lo.y), cell(box.hi.x), cell(box.hi.y), true, false};
  ++count_;
  const long long cells =
      static_cast<long long>(r.x1 - r.x0 + 1) * static_cast<long long>(r.y1 - r.y0 + 1);
  if (cells > kMaxCells || r.x1 < r.x0 || r.y1 < r.y0) {
    r.big = true;
    big_.push_back(f);
    return;
  }
  if (4 * count_ > buckets_.size())
    grow();  // grow() places f too
  else
    place(f);
}

void OverlapGrid::remove(int f) {
  Range& r = range_[f];
  const auto erase = [f](std::vector<int>& v) {
    const auto it = std::find(v.begin(), v.end(), f);
    *it = v.back();
    v.pop_back();
  };
  if (r.big) {
    erase(big_);
  } else {
    for (int x = r.x0; x <= r.x1; ++x)
      for (int y = r.y0; y <= r.y1; ++y) erase(buckets_[bucket(x, y)]);
  }
  r.valid = false;
  --count_;
}

}  // namespace papernet
