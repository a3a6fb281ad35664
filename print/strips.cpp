#include "print/strips.h"

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

  /// Marks every cell that the convex polygon `poly` touches or overlaps, as convex_overlap with
  /// a tolerance of -1e-9 cells does (call runs() afterwards): in each row of cells, those across
  /// the x-range of the polygon's part within the row's band.
  void take(std::span<const Vec2> poly) {
    const double eps = 1e-9 * cell_;
    double x0 = poly[0].x, x1 = x0, y0 = poly[0].y, y1 = y0;
    for (Vec2 p : poly)
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y),
      y1 = std::max(y1, p.y);
    const int i0 = std::max(0, static_cast<int>(std::floor((x0 - lo_.x) / cell_)) - 1);
    const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((x1 - lo_.x) / cell_)) + 1);
    const int j0 = std::max(0, static_cast<int>(std::floor((y0 - lo_.y) / cell_)) - 1);
    const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor((y1 - lo_.y) / cell_)) + 1);
    for (int j = j0; j <= j1; ++j) {
      // The band's x-range of the polygon: its corners within the band and where its sides
      // cross the band's two lines.
      const double b0 = lo_.y + j * cell_ - eps, b1 = lo_.y + (j + 1) * cell_ + eps;
      double a = std::numeric_limits<double>::infinity(), b = -a;
      for (std::size_t k = 0; k < poly.size(); ++k) {
        const Vec2 p = poly[k], q = poly[(k + 1) % poly.size()];
        if (p.y >= b0 && p.y <= b1) a = std::min(a, p.x), b = std::max(b, p.x);
        for (const double line : {b0, b1})
          if ((p.y - line) * (q.y - line) < 0) {
            const double x = p.x + (line - p.y) / (q.y - p.y) * (q.x - p.x);
            a = std::min(a, x), b = std::max(b, x);
          }
      }
      if (!(a <= b)) continue;
      // Cell i spans [lo.x + i cell, lo.x + (i + 1) cell], grown by eps.
      const int ia = std::max(i0, static_cast<int>(std::ceil((a - lo_.x - eps) / cell_)) - 1);
      const int ib = std::min(i1, static_cast<int>(std::floor((b - lo_.x + eps) / cell_)));
      for (int i = ia; i <= ib; ++i) taken_[index(i, j)] = 1;
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

  /// Distance (in cells, chamfer 3-4 metric / 3) from every cell to the nearest taken one, as
  /// the cells are taken now.
  std::vector<float> distances() const {
    constexpr float inf = std::numeric_limits<float>::infinity();
    std::vector<float> d(taken_.size());
    for (std::size_t c = 0; c < d.size(); ++c) d[c] = taken_[c] ? 0.f : inf;
    auto relax = [&](int i, int j, int di, int dj, float w) {
      const int x = i + di, y = j + dj;
      if (x < 0 || y < 0 || x >= nx_ || y >= ny_) return;
      d[index(i, j)] = std::min(d[index(i, j)], d[index(x, y)] + w);
    };
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i)
        relax(i, j, -1, 0, 1), relax(i, j, 0, -1, 1), relax(i, j, -1, -1, 4.f / 3),
            relax(i, j, 1, -1, 4.f / 3);
    for (int j = ny_ - 1; j >= 0; --j)
      for (int i = nx_ - 1; i >= 0; --i)
        relax(i, j, 1, 0, 1), relax(i, j, 0, 1, 1), relax(i, j, 1, 1, 4.f / 3),
            relax(i, j, -1, 1, 4.f / 3);
    return d;
  }
  float at(const std::vector<float>& values, int i, int j) const { return values[index(i, j)]; }

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

/// `corners` grown by `d` on every side (a rectangle).
std::array<Vec2, 4> grown(const std::array<Vec2, 4>& c, double d) {
  const double l = norm(c[1] - c[0]), w = norm(c[3] - c[0]);
  if (!(l > 0 && w > 0)) return c;
  const Vec2 u = (1 / l) * (c[1] - c[0]), v = (1 / w) * (c[3] - c[0]);
  return {c[0] - d * u - d * v, c[1] + d * u - d * v, c[2] + d * u + d * v, c[3] - d * u + d * v};
}

/// The strip `length` x `width` with its lower-left corner (as laid) at `at`, lying along x or
/// standing along y, counter-clockwise.
std::array<Vec2, 4> strip_rect(Vec2 at, double length, double width, bool standing) {
  if (!standing) return {at, at + Vec2{length, 0}, at + Vec2{length, width}, at + Vec2{0, width}};
  const Vec2 r = at + Vec2{width, 0};  // standing: the long side runs up the right edge
  return {r, r + Vec2{0, length}, r + Vec2{-width, length}, r + Vec2{-width, 0}};
}

}  // namespace

std::vector<StripRequest> strip_requests(const std::vector<std::array<Vec2, 3>>& faces,
                                         const std::vector<NetEdge>& edges,
                                         const std::vector<int>& which,
                                         const StripOptions& options) {
  std::vector<StripRequest> out;
  for (int e : which) {
    const EdgeSide s = edges[e].a;
    const double len = norm(faces[s.face][(s.k + 1) % 3] - faces[s.face][s.k]);
    const double half = std::clamp(0.5 * len, options.min_half_width,
                                   std::max(options.min_half_width, options.max_half_width));
    const Vec2 mid = 0.5 * (faces[s.face][s.k] + faces[s.face][(s.k + 1) % 3]);
    out.push_back({e, std::max(len, options.min_length), 2 * half, mid});
  }
  return out;
}

std::vector<GlueStrip> place_strips(const std::vector<std::array<Vec2, 3>>& faces,
                                    const std::vector<Tab>& tabs,
                                    const std::vector<StripRequest>& requests,
                                    const std::vector<GlueStrip>& others,
                                    const StripOptions& options) {
  std::vector<GlueStrip> out;
  if (requests.empty()) return out;
  using Size = StripRequest;
  const std::vector<Size>& sizes = requests;
  double longest = 0;
  for (const Size& r : requests) longest = std::max(longest, r.length);
  // Smallest first: length and width both grow with the edge's length, so once a strip finds
  // no room inside the box, no later one can (placing strips only takes room away).
  std::vector<int> order(sizes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return std::pair{sizes[a].length, sizes[a].width} < std::pair{sizes[b].length, sizes[b].width};
  });

  Box2 box = Box2::empty();
  double mean_edge = 0;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) box.add(f[k]), mean_edge += norm(f[(k + 1) % 3] - f[k]);
  for (const Tab& t : tabs)
    for (Vec2 p : t.corners) box.add(p);
  for (const GlueStrip& t : others)
    for (Vec2 p : t.corners) box.add(p);
  const Vec2 lo = box.lo, hi = box.hi;
  mean_edge /= std::max<double>(1, 3.0 * static_cast<double>(faces.size()));

  PolygonGrid grid(std::max({mean_edge, longest, 1e-9}));
  for (const auto& f : faces) grid.add(f);
  for (const Tab& t : tabs) grid.add(t.corners);
  for (const GlueStrip& t : others) grid.add(t.corners);
  const double cell = options.cell, gap = options.gap, tolerance = 1e-6;
  FreeSpace space(lo, hi, cell);
  for (const auto& f : faces) space.take(f);
  for (const Tab& t : tabs) space.take(t.corners);
  for (const GlueStrip& t : others) space.take(grown(t.corners, gap));
  space.runs();
  const std::vector<float> distance = space.distances();

  const int gc = static_cast<int>(std::ceil(gap / cell));
  // A window [i, i + cw) x [j, j + ch) lies inside one of options.within (when there are any).
  auto allowed = [&](int i, int j, int cw, int ch) {
    if (options.within.empty()) return true;
    const Vec2 a = space.corner(i, j), b = space.corner(i + cw, j + ch);
    for (const auto& [wlo, whi] : options.within)
      if (a.x >= wlo.x && a.y >= wlo.y && b.x <= whi.x && b.y <= whi.y) return true;
    return false;
  };
  // Tries the window of strip `s` centred on cell (ci, cj), lying or standing.
  // The window must hug the net (its centre at most `hug` beyond its half size from a face or
  // tab): a strip out in the open would print on pages that show nothing else.
  const double hug = options.hug / cell;
  auto try_at = [&](const Size& s, int ci, int cj, bool hugging = true) {
    for (bool standing : {false, true}) {
      const double w = standing ? s.width : s.length, h = standing ? s.length : s.width;
      const int cw = static_cast<int>(std::ceil(w / cell)) + 2 * gc;
      const int ch = static_cast<int>(std::ceil(h / cell)) + 2 * gc;
      const int i = ci - cw / 2, j = cj - ch / 2;
      if (i < 0 || j < 0 || i + cw > space.nx() || j + ch > space.ny() ||
          (hugging && space.at(distance, ci, cj) > 0.5 * std::max(cw, ch) + hug) ||
          !allowed(i, j, cw, ch) || !space.free(i, j, cw, ch))
        continue;
      const auto rect = strip_rect(space.corner(i + gc, j + gc), s.length, s.width, standing);
      if (grid.overlaps(rect, tolerance)) continue;  // the raster is conservative: never
      grid.add(rect);
      space.take_cells(i, j, cw, ch);
      out.push_back({s.edge, rect, {}, 0});
      return true;
    }
    return false;
  };
  // Each strip goes to the free window nearest its edge (rings of growing Chebyshev radius
  // around the edge's middle, up to `search_radius`), so that it is printed on the same page
  // as its edge where it can be.
  const int radius = static_cast<int>(std::ceil(options.search_radius / cell));
  auto cell_of = [&](Vec2 p) {
    return std::pair{static_cast<int>(std::floor((p.x - lo.x) / cell)),
                     static_cast<int>(std::floor((p.y - lo.y) / cell))};
  };
  // Whether `place` puts strip `s` on a cell of the rings around its edge's middle, nearest
  // first, out to radius `rings`, within cells [i0, i1] x [j0, j1].
  auto ring_search = [&](const Size& s, int rings, int i0, int j0, int i1, int j1, auto place) {
    const auto [ti, tj] = cell_of(s.near);
    for (int r = 0; r <= rings; ++r)
      for (int k = 0; k < std::max(1, 8 * r); ++k) {
        // The k-th cell of the ring of radius r: walk its four sides.
        const int side = r > 0 ? k / (2 * r) : 0, t = r > 0 ? k % (2 * r) : 0;
        const int di = side == 0 ? -r + t : side == 1 ? r : side == 2 ? r - t : -r;
        const int dj = side == 0 ? -r : side == 1 ? -r + t : side == 2 ? r : r - t;
        const int ci = ti + di, cj = tj + dj;
        if (ci < i0 || cj < j0 || ci > i1 || cj > j1) continue;
        if (place(ci, cj)) return true;
      }
    return false;
  };
  std::vector<int> far;  // strips with no room near their edge
  for (int o : order) {
    const Size& s = sizes[o];
    const double limit = 0.5 * (std::ceil(s.length / cell) + 2 * gc) + hug;
    const bool placed =
        ring_search(s, radius, 0, 0, space.nx() - 1, space.ny() - 1, [&](int ci, int cj) {
          // too far from the net for this strip either way
          return space.at(distance, ci, cj) <= limit && try_at(s, ci, cj);
        });
    if (!placed) far.push_back(o);
  }
  // Then, when strips must lie in boxes (the sheets of a fit layout), the free window nearest
  // the edge anywhere in the edge's own box, out in the open too: that sheet prints anyway.
  // Largest first, so that small strips fill what large ones leave.
  if (options.nearest_in_box && !options.within.empty()) {
    std::vector<int> still;
    // Per box, the sizes that found no room in it: no strip as long and as wide will.
    std::vector<std::vector<std::pair<double, double>>> full(options.within.size());
    for (auto it = far.rbegin(); it != far.rend(); ++it) {
      const Size& s = sizes[*it];
      std::size_t b = 0;
      while (b < options.within.size() &&
             !(s.near.x >= options.within[b].first.x && s.near.y >= options.within[b].first.y &&
               s.near.x <= options.within[b].second.x && s.near.y <= options.within[b].second.y))
        ++b;
      const bool hopeless =
          b == options.within.size() ||
          std::any_of(full[b].begin(), full[b].end(), [&](const std::pair<double, double>& f) {
            return s.length >= f.first && s.width >= f.second;
          });
      if (!hopeless) {
        const auto [i0, j0] = cell_of(options.within[b].first);
        const auto [i1, j1] = cell_of(options.within[b].second);
        const auto [ti, tj] = cell_of(s.near);
        const int rings = std::max({ti - i0, i1 - ti, tj - j0, j1 - tj});
        if (ring_search(s, rings, std::max(0, i0), std::max(0, j0), std::min(space.nx() - 1, i1),
                        std::min(space.ny() - 1, j1),
                        [&](int ci, int cj) { return try_at(s, ci, cj, false); }))
          continue;
        full[b].emplace_back(s.length, s.width);
      }
      still.push_back(*it);
    }
    // The scan below takes them smallest first.
    std::reverse(still.begin(), still.end());
    far = std::move(still);
  }
  // Then anywhere in the box, scanning rows from the top, left to right. Strips come in growing
  // sizes and space only shrinks, so no window before the last strip's can hold the next: the
  // scan resumes there.
  std::vector<int> left;  // strips with no room inside the box
  int cursor = 0;  // scan position: (ny - 1 - cursor / nx) is the row, cursor % nx the column
  for (int o : far) {
    const Size& s = sizes[o];
    if (!left.empty() && s.length >= sizes[left.front()].length &&
        s.width >= sizes[left.front()].width) {  // a smaller strip found no room: nor does this
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
        if (i + cw > space.nx() || j - ch + 1 < 0 || !allowed(i, j - ch + 1, cw, ch) ||
            !space.free(i, j - ch + 1, cw, ch))
          continue;
        const auto rect =
            strip_rect(space.corner(i + gc, j - ch + 1 + gc), s.length, s.width, standing);
        if (grid.overlaps(rect, tolerance)) continue;
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
