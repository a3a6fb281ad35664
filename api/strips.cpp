#include "api/strips.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace papernet {

namespace {

/// Occupancy raster of [lo, lo + n * cell]: which cells are taken, and for each cell how many
/// free cells run from it to the right (so a w x h window is checked in h steps).
class FreeSpace {
 public:
  FreeSpace(Vec2 lo, Vec2 hi, double cell)
      : lo_(lo),
        cell_(cell),
        nx_(std::max(1, static_cast<int>(std::ceil((hi.x - lo.x) / cell)))),
        ny_(std::max(1, static_cast<int>(std::ceil((hi.y - lo.y) / cell)))),
        taken_(static_cast<std::size_t>(nx_) * ny_, 0),
        run_(taken_.size(), 0) {}

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  Vec2 corner(int i, int j) const { return lo_ + Vec2{i * cell_, j * cell_}; }

  /// Marks every cell that `poly` touches or overlaps (call runs() afterwards).
  void take(std::span<const Vec2> poly) {
    double x0 = poly[0].x, x1 = x0, y0 = poly[0].y, y1 = y0;
    for (Vec2 p : poly)
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y),
      y1 = std::max(y1, p.y);
    const int i0 = std::max(0, static_cast<int>(std::floor((x0 - lo_.x) / cell_)) - 1);
    const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((x1 - lo_.x) / cell_)) + 1);
    const int j0 = std::max(0, static_cast<int>(std::floor((y0 - lo_.y) / cell_)) - 1);
    const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor((y1 - lo_.y) / cell_)) + 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Vec2 c = corner(i, j);
        const std::array<Vec2, 4> box = {c, c + Vec2{cell_, 0}, c + Vec2{cell_, cell_},
                                         c + Vec2{0, cell_}};
        if (convex_overlap(poly, box, -1e-9 * cell_)) taken_[index(i, j)] = 1;
      }
  }

  /// Takes cells [i, i + w) x [j, j + h) and updates their rows' runs.
  void take_cells(int i, int j, int w, int h) {
    for (int y = j; y < j + h; ++y) {
      for (int x = i; x < i + w; ++x) taken_[index(x, y)] = 1;
      row_runs(y);
    }
  }

  void runs() {
    for (int j = 0; j < ny_; ++j) row_runs(j);
  }

  /// True when cells [i, i + w) x [j, j + h) are all free.
  bool free(int i, int j, int w, int h) const {
    for (int y = j; y < j + h; ++y)
      if (run_[index(i, y)] < w) return false;
    return true;
  }

 private:
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * nx_ + i; }
  void row_runs(int j) {
    int run = 0;
    for (int i = nx_ - 1; i >= 0; --i) run_[index(i, j)] = run = taken_[index(i, j)] ? 0 : run + 1;
  }

  Vec2 lo_;
  double cell_;
  int nx_, ny_;
  std::vector<unsigned char> taken_;
  std::vector<int> run_;
};

/// The strip `length` x `width` with its lower-left corner (as laid) at `at`, lying along x or
/// standing along y, counter-clockwise.
std::array<Vec2, 4> strip_rect(Vec2 at, double length, double width, bool standing) {
  if (!standing) return {at, at + Vec2{length, 0}, at + Vec2{length, width}, at + Vec2{0, width}};
  const Vec2 r = at + Vec2{width, 0};  // standing: the long side runs up the right edge
  return {r, r + Vec2{0, length}, r + Vec2{-width, length}, r + Vec2{-width, 0}};
}

}  // namespace

std::vector<GlueStrip> place_strips(const std::vector<std::array<Vec2, 3>>& faces,
                                    const std::vector<Tab>& tabs, const std::vector<NetEdge>& edges,
                                    const std::vector<int>& which, const StripOptions& options) {
  std::vector<GlueStrip> out;
  if (which.empty()) return out;
  struct Size {
    int edge;
    double length, width;
  };
  std::vector<Size> sizes;
  double longest = 0;
  for (int e : which) {
    const EdgeSide s = edges[e].a;
    const double len = norm(faces[s.face][(s.k + 1) % 3] - faces[s.face][s.k]);
    const double half = std::clamp(0.5 * len, options.min_half_width,
                                   std::max(options.min_half_width, options.max_half_width));
    sizes.push_back({e, std::max(len, options.min_length), 2 * half});
    longest = std::max(longest, sizes.back().length);
  }
  // Smallest first: length and width both grow with the edge's length, so once a strip finds
  // no room inside the box, no later one can (placing strips only takes room away).
  std::vector<int> order(sizes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return sizes[a].length < sizes[b].length; });

  constexpr double inf = std::numeric_limits<double>::infinity();
  Vec2 lo{inf, inf}, hi{-inf, -inf};
  auto grow = [&](Vec2 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  };
  double mean_edge = 0;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) grow(f[k]), mean_edge += norm(f[(k + 1) % 3] - f[k]);
  for (const Tab& t : tabs)
    for (Vec2 p : t.corners) grow(p);
  mean_edge /= std::max<double>(1, 3.0 * static_cast<double>(faces.size()));

  PolygonGrid grid(std::max({mean_edge, longest, 1e-9}));
  for (const auto& f : faces) grid.add(f);
  for (const Tab& t : tabs) grid.add(t.corners);
  const double cell = options.cell, gap = options.gap, tolerance = 1e-6;
  FreeSpace space(lo, hi, cell);
  for (const auto& f : faces) space.take(f);
  for (const Tab& t : tabs) space.take(t.corners);
  space.runs();

  // First fit, scanning rows from the top, left to right. Strips come in growing sizes and
  // space only shrinks, so no window before the last strip's can hold the next: the scan resumes
  // there.
  std::vector<int> left;  // strips with no room inside the box
  const int gc = static_cast<int>(std::ceil(gap / cell));
  int cursor = 0;  // scan position: (ny - 1 - cursor / nx) is the row, cursor % nx the column
  for (int o : order) {
    const Size& s = sizes[o];
    if (!left.empty()) {  // a smaller strip found no room: neither does this one
      left.push_back(o);
      continue;
    }
    bool placed = false;
    for (; cursor < space.nx() * space.ny() && !placed; ++cursor) {
      const int j = space.ny() - 1 - cursor / space.nx(), i = cursor % space.nx();
      for (bool standing : {false, true}) {
        const double w = standing ? s.width : s.length, h = standing ? s.length : s.width;
        const int cw = static_cast<int>(std::ceil(w / cell)) + 2 * gc;
        const int ch = static_cast<int>(std::ceil(h / cell)) + 2 * gc;
        if (i + cw > space.nx() || j - ch + 1 < 0 || !space.free(i, j - ch + 1, cw, ch)) continue;
        const auto rect =
            strip_rect(space.corner(i + gc, j - ch + 1 + gc), s.length, s.width, standing);
        if (grid.overlaps(rect, tolerance)) continue;  // the raster is conservative: never
        grid.add(rect);
        space.take_cells(i, j - ch + 1, cw, ch);
        out.push_back({s.edge, rect, {}, 0});
        placed = true;
        break;
      }
      if (placed) break;
    }
    if (!placed) left.push_back(o);
  }

  // Rows below the box, as wide as the box (or the longest strip).
  const double row_width = std::max(hi.x - lo.x, longest + 2 * gap);
  double x = lo.x, top = lo.y, row_height = 0;
  for (int o : left) {
    const Size& s = sizes[o];
    if (x > lo.x && x + s.length + 2 * gap > lo.x + row_width)
      x = lo.x, top -= row_height, row_height = 0;
    auto rect = strip_rect({x + gap, top - gap - s.width}, s.length, s.width, false);
    while (grid.overlaps(rect, tolerance))  // cannot happen below the box; stay safe anyway
      for (Vec2& p : rect) p = p - Vec2{0, s.width + gap};
    grid.add(rect);
    out.push_back({s.edge, rect, {}, 0});
    x += s.length + 2 * gap;
    row_height = std::max(row_height, s.width + 2 * gap);
  }
  return out;
}

StripMarks strip_marks(const GlueStrip& strip) {
  const auto& c = strip.corners;
  const Vec2 along = c[1] - c[0], across = c[3] - c[0];
  const double width = norm(across);
  const Vec2 n = width > 0 ? (1 / width) * across : Vec2{0, 1};
  StripMarks m;
  m.seam0 = c[0] + 0.5 * across;
  m.seam1 = c[1] + 0.5 * (c[2] - c[1]);
  const Vec2 mid = 0.5 * (m.seam0 + m.seam1);
  m.label_at = {mid - (0.25 * width) * n, mid + (0.25 * width) * n};
  m.angle = std::atan2(along.y, along.x);
  m.half_width = 0.5 * width;
  return m;
}

}  // namespace papernet
