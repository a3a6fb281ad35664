#include "print/internal/nest_outlines.h"

#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>

namespace papernet::print_detail {
namespace {

// The grid's cell, in the parts' units (micrometres): half a millimetre.
constexpr std::int64_t kCell = 500;

// Polygons grow by this much more before they are rasterised by their cells' centres, so that every
// cell a grown polygon touches is marked (half the cell's diagonal, and some to spare).
constexpr double kCover = 0.72 * kCell;

/// Cells of a grid as rows of 64-bit words; bit i of a row is cell i.
class Bits {
 public:
  Bits() = default;
  Bits(int width, int height)
      : width_(width),
        height_(height),
        words_((width + 63) / 64),
        bits_(static_cast<std::size_t>(words_) * height, 0) {}
  int width() const { return width_; }
  int height() const { return height_; }
  std::uint64_t word(int row, int w) const {
    return bits_[static_cast<std::size_t>(row) * words_ + w];
  }
  /// The 64 cells of row `row` from cell `x` on (bit 0 is cell x; cells past the row are 0).
  std::uint64_t from(int row, int x) const {
    const int w = x / 64, by = x % 64;
    std::uint64_t v = w < words_ ? word(row, w) >> by : 0;
    if (by != 0 && w + 1 < words_) v |= word(row, w + 1) << (64 - by);
    return v;
  }
  /// Sets cells x0 to x1 (inclusive) of row y.
  void set_span(int x0, int x1, int y) {
    for (int w = x0 / 64; w <= x1 / 64; ++w) {
      const int lo = std::max(x0 - 64 * w, 0), hi = std::min(x1 - 64 * w, 63);
      const std::uint64_t up_to_hi =
          hi == 63 ? ~std::uint64_t{0} : (std::uint64_t{1} << (hi + 1)) - 1;
      bits_[static_cast<std::size_t>(y) * words_ + w] |= up_to_hi & ~((std::uint64_t{1} << lo) - 1);
    }
  }
  /// ORs `bits` into word `w` of row `row`.
  void add(int row, int w, std::uint64_t bits) {
    bits_[static_cast<std::size_t>(row) * words_ + w] |= bits;
  }
  /// Cells set in row `row`.
  int count(int row) const {
    int n = 0;
    for (int w = 0; w < words_; ++w) n += std::popcount(word(row, w));
    return n;
  }
  /// The cell of the `n`th set cell of row `row` (from 0; fewer than n + 1 set: width()).
  int nth_set(int row, int n) const {
    for (int w = 0; w < words_; ++w) {
      std::uint64_t bits = word(row, w);
      const int here = std::popcount(bits);
      if (n >= here) {
        n -= here;
        continue;
      }
      for (; n > 0; --n) bits &= bits - 1;
      return 64 * w + std::countr_zero(bits);
    }
    return width_;
  }
  /// The longest run of cells of row `row` that are set (`set`) or not.
  int longest_run(int row, bool set) const {
    int best = 0;
    for (int x = next(row, 0, set); x < width_;) {
      const int end = next(row, x, !set);
      best = std::max(best, end - x);
      x = next(row, end, set);
    }
    return best;
  }
  /// Word `w` of row `row` shifted `by` (0 to 63) cells to the right: its own bits moved up, and
  /// the top bits of the word before it.
  std::uint64_t shifted(int row, int w, int by) const {
    std::uint64_t v = w < words_ ? word(row, w) << by : 0;
    if (by != 0 && w > 0) v |= word(row, w - 1) >> (64 - by);
    return v;
  }

 private:
  // The first cell from x on in row `row` that is set (`set`) or not; width_ when none is.
  int next(int row, int x, bool set) const {
    for (; x < width_; x += 64 - x % 64) {
      const std::uint64_t w = set ? word(row, x / 64) >> (x % 64) : ~word(row, x / 64) >> (x % 64);
      if (w != 0) return std::min(width_, x + std::countr_zero(w));
    }
    return width_;
  }

  int width_ = 0, height_ = 0, words_ = 0;
  std::vector<std::uint64_t> bits_;
};

/// A part turned, as cells: `mask` cell (i, j) is the grid's cell (i + x, j + y) when the
/// turned part is moved by (x - ox, y - oy) cells.
struct Shape {
  double angle = 0;
  std::int64_t ox = 0, oy = 0;  ///< the mask's first cell in the turned part's frame
  Bits mask;
  double area = 0;
  /// Some of the mask's cells, spread over it: a place where one of them meets a marked cell
  /// of the sheet is ruled out before the whole mask is compared.
  std::vector<std::pair<int, int>> probes;
  /// More of them, spread alike: a place that the first probes leave open is tested on these
  /// before the whole mask is compared.
  std::vector<std::pair<int, int>> more_probes;
  std::size_t cells = 0;  ///< cells of the mask
  /// The mask's widest rows (row, longest run of its cells in that row), widest first: a place
  /// where the sheet's row under one of them has no free run as long is ruled out at once.
  std::vector<std::pair<int, int>> widest;
  /// Bands of the mask: `height` rows in a row, each with a run of at least `run` cells. A sheet
  /// without as many rows in a row, each with a free run that long, has no place for the mask.
  struct Band {
    int height = 0, run = 0;
  };
  std::vector<Band> bands;
};

// How many of a mask's widest rows a place's rows are compared with first (Shape::widest).
constexpr std::size_t kWidestRows = 3;

/// A sheet's cells, with what rules out places quickly: the longest run of free cells of each
/// row, the longest of all rows, and the free cells in all.
struct Sheet {
  Sheet(int cols, int rows)
      : cells(cols, rows),
        free_run(static_cast<std::size_t>(rows), cols),
        free(static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows)),
        tallest(static_cast<std::size_t>(cols) + 1, rows),
        leaves(static_cast<int>(std::bit_ceil(static_cast<unsigned>(std::max(rows, 1))))),
        most(2 * static_cast<std::size_t>(leaves), -1) {
    update_most(0, rows);
  }
  Bits cells;
  std::vector<int> free_run;
  std::size_t free;
  /// tallest[run]: the most rows in a row that each have a free run of at least `run` cells.
  std::vector<int> tallest;
  /// The longest free runs as a tree of maxima: most[leaves + r] is row r's, most[k] the larger of
  /// most[2k] and most[2k + 1] (-1 past the last row), so that the next row with a free run as
  /// long as a part's widest row needs is found in a step down the tree (next_row).
  int leaves;
  std::vector<int> most;

  /// The tree above rows [from, to) again, after their free runs changed.
  void update_most(int from, int to) {
    for (int r = from; r < to; ++r)
      most[static_cast<std::size_t>(leaves + r)] = free_run[static_cast<std::size_t>(r)];
    for (int lo = (leaves + from) / 2, hi = (leaves + to - 1) / 2; lo >= 1; lo /= 2, hi /= 2)
      for (int k = lo; k <= hi; ++k)
        most[static_cast<std::size_t>(k)] = std::max(most[2 * static_cast<std::size_t>(k)],
                                                     most[2 * static_cast<std::size_t>(k) + 1]);
  }

  /// The longest free run of all rows (-1 on a sheet without rows).
  int widest_free() const { return most[1]; }

  /// The first row from `row` on whose free run is at least `run` cells; the rows' count when
  /// none is.
  int next_row(int row, int run) const {
    const auto rows = static_cast<int>(free_run.size());
    if (row >= rows) return rows;
    auto k = static_cast<std::size_t>(leaves + row);
    if (most[k] >= run) return row;
    // Up while the subtree to the right holds no such row, then down its leftmost such leaf.
    for (;; k /= 2) {
      if (k == 1) return rows;
      if (k % 2 == 0 && most[k + 1] >= run) {
        ++k;
        break;
      }
    }
    while (k < static_cast<std::size_t>(leaves)) k = most[2 * k] >= run ? 2 * k : 2 * k + 1;
    return std::min(static_cast<int>(k) - leaves, rows);
  }
};

// Sheet::tallest from Sheet::free_run. Each row, with the rows around it up to the first row of
// a shorter free run either way, makes a stretch whose shortest free run is the row's own; the
// stretch counts for every run up to that one. The stretches are found with a stack of rows whose
// free runs increase.
void find_tallest(Sheet& sheet) {
  const auto rows = static_cast<int>(sheet.free_run.size());
  std::fill(sheet.tallest.begin(), sheet.tallest.end(), 0);
  std::vector<int> stack;
  for (int r = 0; r <= rows; ++r) {
    const int run = r < rows ? sheet.free_run[static_cast<std::size_t>(r)] : -1;
    while (!stack.empty() && sheet.free_run[static_cast<std::size_t>(stack.back())] >= run) {
      const int low = sheet.free_run[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      const int from = stack.empty() ? 0 : stack.back() + 1;
      int& t = sheet.tallest[static_cast<std::size_t>(low)];
      t = std::max(t, r - from);
    }
    stack.push_back(r);
  }
  for (auto run = static_cast<int>(sheet.tallest.size()) - 2; run >= 0; --run)
    sheet.tallest[static_cast<std::size_t>(run)] =
        std::max(sheet.tallest[static_cast<std::size_t>(run)],
                 sheet.tallest[static_cast<std::size_t>(run) + 1]);
}

// How many cells of a mask are probed first (Shape::probes), and then (Shape::more_probes).
constexpr std::size_t kProbes = 24;
constexpr std::size_t kMoreProbes = 256;

// How many times the parts of the last sheet are moved to the front of the order at most (each
// time that saves a sheet).
constexpr int kLastSheetRounds = 3;

// The mask's counts, bands and probes (Shape::cells, widest, bands, probes, more_probes).
void finish(Shape& shape) {
  const int h = shape.mask.height();
  std::vector<std::pair<int, int>> runs;                                // (row, longest run)
  std::vector<std::size_t> before(static_cast<std::size_t>(h) + 1, 0);  // cells in rows before
  for (int j = 0; j < h; ++j) {
    before[static_cast<std::size_t>(j) + 1] =
        before[static_cast<std::size_t>(j)] + static_cast<std::size_t>(shape.mask.count(j));
    runs.emplace_back(j, shape.mask.longest_run(j, true));
  }
  shape.cells = before.back();
  // The tallest band of rows with runs of a quarter, and of half, the widest run.
  int widest_run = 0;
  for (const auto& [j, run] : runs) widest_run = std::max(widest_run, run);
  for (const int share : {4, 2}) {
    const int least = std::max(1, widest_run / share);
    Shape::Band band;
    for (int j = 0; j < h;) {
      int end = j;
      while (end < h && runs[static_cast<std::size_t>(end)].second >= least) ++end;
      if (end - j > band.height) band = {end - j, least};
      j = end + 1;
    }
    if (band.height > 1) shape.bands.push_back(band);
  }
  // The widest rows, the lower first among equals.
  shape.widest.clear();
  for (const auto& row : runs) {
    const auto at = std::find_if(shape.widest.begin(), shape.widest.end(),
                                 [&](const auto& w) { return w.second < row.second; });
    if (at == shape.widest.end() && shape.widest.size() == kWidestRows) continue;
    shape.widest.insert(at, row);
    if (shape.widest.size() > kWidestRows) shape.widest.pop_back();
  }
  // Every step-th cell, in rows from the first, from the middle of the first step on.
  const auto spread = [&](std::size_t count, std::vector<std::pair<int, int>>& out) {
    const std::size_t step = std::max<std::size_t>(1, shape.cells / count);
    for (std::size_t next = step / 2, j = 0; next < shape.cells; next += step) {
      while (before[j + 1] <= next) ++j;
      out.emplace_back(shape.mask.nth_set(static_cast<int>(j), static_cast<int>(next - before[j])),
                       static_cast<int>(j));
    }
  };
  spread(kProbes, shape.probes);
  spread(kMoreProbes, shape.more_probes);
}

// The mask without its empty rows and columns at the borders (the fringe of kCover).
void trim(Shape& shape) {
  const Bits& m = shape.mask;
  int x0 = m.width(), x1 = -1, y0 = m.height(), y1 = -1;
  for (int j = 0; j < m.height(); ++j)
    for (int w = 0; w < (m.width() + 63) / 64; ++w) {
      const std::uint64_t bits = m.word(j, w);
      if (bits == 0) continue;
      y0 = std::min(y0, j), y1 = std::max(y1, j);
      x0 = std::min(x0, 64 * w + std::countr_zero(bits));
      x1 = std::max(x1, 64 * w + 63 - std::countl_zero(bits));
    }
  if (y1 < 0) {
    shape.mask = Bits();
    return;
  }
  if (x0 == 0 && y0 == 0 && x1 == m.width() - 1 && y1 == m.height() - 1) return;
  Bits out(x1 - x0 + 1, y1 - y0 + 1);
  for (int j = y0; j <= y1; ++j)
    for (int w = 0; w < (out.width() + 63) / 64; ++w) {
      std::uint64_t bits = m.from(j, x0 + 64 * w);
      const int left = out.width() - 64 * w;
      if (left < 64) bits &= (std::uint64_t{1} << left) - 1;
      out.add(j - y0, w, bits);
    }
  shape.ox += x0;
  shape.oy += y0;
  shape.mask = std::move(out);
}

// The cells of a part's polygons, grown by `grow`, as it comes (turned 0).
Shape rasterise(const std::vector<std::vector<IntPoint>>& polygons, std::int64_t grow) {
  Shape shape;
  // Each polygon grown on its own: no union of a piece's faces, which Clipper's can get stuck on
  // (slivers of CAD models met in FixupIntersectionOrder), and the grown polygons' cells together
  // are those of the grown union.
  std::vector<ClipperLib::Paths> grown(polygons.size());
  std::int64_t lo_x = std::numeric_limits<std::int64_t>::max(), lo_y = lo_x;
  std::int64_t hi_x = std::numeric_limits<std::int64_t>::min(), hi_y = hi_x;
  ClipperLib::ClipperOffset offset;
  for (std::size_t k = 0; k < polygons.size(); ++k) {
    ClipperLib::Path path;
    for (const IntPoint& p : polygons[k]) path.push_back({p.x, p.y});
    const double area = std::abs(ClipperLib::Area(path));
    shape.area += area;
    offset.Clear();
    // A polygon without area (a sliver) grows as the lines it is.
    offset.AddPath(path, ClipperLib::jtMiter,
                   area > 0 ? ClipperLib::etClosedPolygon : ClipperLib::etOpenSquare);
    offset.Execute(grown[k], static_cast<double>(grow) + kCover);
    for (const auto& g : grown[k])
      for (const auto& p : g) {
        lo_x = std::min<std::int64_t>(lo_x, p.X), hi_x = std::max<std::int64_t>(hi_x, p.X);
        lo_y = std::min<std::int64_t>(lo_y, p.Y), hi_y = std::max<std::int64_t>(hi_y, p.Y);
      }
  }
  if (lo_x > hi_x) return shape;
  auto cell_of = [](std::int64_t v) {
    return static_cast<std::int64_t>(std::floor(static_cast<double>(v) / kCell));
  };
  shape.ox = cell_of(lo_x);
  shape.oy = cell_of(lo_y);
  const auto w = static_cast<int>(cell_of(hi_x) - shape.ox + 1);
  const auto h = static_cast<int>(cell_of(hi_y) - shape.oy + 1);
  shape.mask = Bits(w, h);
  // Each grown polygon's cells whose centres lie inside it (even-odd over its paths), row by row
  // over its own rows.
  std::vector<double> xs;
  for (const ClipperLib::Paths& paths : grown) {
    std::int64_t top = std::numeric_limits<std::int64_t>::max(), bottom = -top;
    for (const auto& g : paths)
      for (const auto& p : g)
        top = std::min<std::int64_t>(top, p.Y), bottom = std::max<std::int64_t>(bottom, p.Y);
    if (top > bottom) continue;
    const int j0 = std::max(0, static_cast<int>(cell_of(top) - shape.oy));
    const int j1 = std::min(h - 1, static_cast<int>(cell_of(bottom) - shape.oy));
    for (int j = j0; j <= j1; ++j) {
      const double y = (static_cast<double>(shape.oy + j) + 0.5) * kCell;
      xs.clear();
      for (const auto& g : paths)
        for (std::size_t k = 0; k < g.size(); ++k) {
          const auto& a = g[k];
          const auto& b = g[(k + 1) % g.size()];
          const double ay = static_cast<double>(a.Y), by = static_cast<double>(b.Y);
          if ((ay <= y) == (by <= y)) continue;
          xs.push_back(static_cast<double>(a.X) +
                       (y - ay) * static_cast<double>(b.X - a.X) / (by - ay));
        }
      std::sort(xs.begin(), xs.end());
      for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
        const auto from = static_cast<int>(std::ceil(xs[k] / kCell - 0.5 - shape.ox));
        const auto to = static_cast<int>(std::floor(xs[k + 1] / kCell - 0.5 - shape.ox));
        if (std::max(0, from) <= std::min(w - 1, to))
          shape.mask.set_span(std::max(0, from), std::min(w - 1, to), j);
      }
    }
  }
  trim(shape);
  finish(shape);
  return shape;
}

// Transposes a 64 x 64 block of cells: afterwards bit c of row r is what bit r of row c was.
void transpose(std::array<std::uint64_t, 64>& rows) {
  std::uint64_t keep = 0x00000000FFFFFFFFull;  // the low half of each bit pair swapped next
  for (int half = 32; half != 0; half >>= 1, keep ^= keep << half)
    for (int k = 0; k < 64; k = ((k | half) + 1) & ~half) {
      const std::uint64_t swap = ((rows[k] >> half) ^ rows[k | half]) & keep;
      rows[k | half] ^= swap;
      rows[k] ^= swap << half;
    }
}

// `shape` turned a quarter more, counter-clockwise about the origin, as `angle`: the grid maps onto
// itself (cell (i, j) onto cell (-j - 1, i)), and so do the cells a polygon covers, but for
// polygons whose edges run through cells' centres, which either way are a fringe kCover beyond
// the cells the part touches.
Shape quarter_turned(const Shape& shape, double angle) {
  Shape out;
  out.angle = angle;
  out.area = shape.area;
  const int w = shape.mask.width(), h = shape.mask.height();
  out.ox = -(shape.oy + h);
  out.oy = shape.ox;
  out.mask = Bits(h, w);
  // Cell (i, j) goes to (h - 1 - j, i), 64 x 64 cells at a time: the rows j of the block taken
  // from the last up are the block's columns turned.
  std::array<std::uint64_t, 64> block;
  for (int a = 0; a < (h + 63) / 64; ++a)
    for (int k = 0; k < (w + 63) / 64; ++k) {
      for (int t = 0; t < 64; ++t) {
        const int j = h - 1 - (64 * a + t);
        block[static_cast<std::size_t>(t)] = j >= 0 ? shape.mask.word(j, k) : 0;
      }
      transpose(block);
      for (int c = 0; c < 64 && 64 * k + c < w; ++c)
        out.mask.add(64 * k + c, a, block[static_cast<std::size_t>(c)]);
    }
  finish(out);
  return out;
}

// The 64 bits of `v` in the reverse order.
std::uint64_t reversed(std::uint64_t v) {
  v = ((v >> 1) & 0x5555555555555555ull) | ((v & 0x5555555555555555ull) << 1);
  v = ((v >> 2) & 0x3333333333333333ull) | ((v & 0x3333333333333333ull) << 2);
  v = ((v >> 4) & 0x0F0F0F0F0F0F0F0Full) | ((v & 0x0F0F0F0F0F0F0F0Full) << 4);
  v = ((v >> 8) & 0x00FF00FF00FF00FFull) | ((v & 0x00FF00FF00FF00FFull) << 8);
  v = ((v >> 16) & 0x0000FFFF0000FFFFull) | ((v & 0x0000FFFF0000FFFFull) << 16);
  return (v >> 32) | (v << 32);
}

// `shape` turned half round about the origin, as `angle`: cell (i, j) goes to (-i - 1, -j - 1),
// so the mask's cell (i, j) is the old mask's (w - 1 - i, h - 1 - j). What finish() counts comes
// from the shape's own: the same cells and bands; the widest rows and the probes are the same
// cells turned (any of a mask's cells rules places out alike).
Shape half_turned(const Shape& shape, double angle) {
  Shape out;
  out.angle = angle;
  out.area = shape.area;
  const int w = shape.mask.width(), h = shape.mask.height();
  out.ox = -(shape.ox + w);
  out.oy = -(shape.oy + h);
  out.mask = Bits(w, h);
  // Row j is the old row h - 1 - j read backwards (new cell i is old cell w - 1 - i): the old
  // words reversed, the last first, less the `spare` cells past the row's width that lead them.
  const int words = (w + 63) / 64, spare = 64 * words - w;
  for (int j = 0; j < h; ++j)
    for (int k = 0; k < words; ++k) {
      const int last = words - 1 - k;  // the old word that, reversed, word k starts with
      std::uint64_t v = reversed(shape.mask.word(h - 1 - j, last)) >> spare;
      if (spare != 0 && last > 0)
        v |= reversed(shape.mask.word(h - 1 - j, last - 1)) << (64 - spare);
      out.mask.add(j, k, v);
    }
  out.cells = shape.cells;
  out.bands = shape.bands;
  for (const auto& [j, run] : shape.widest) out.widest.emplace_back(h - 1 - j, run);
  std::stable_sort(out.widest.begin(), out.widest.end(), [](const auto& a, const auto& b) {
    return a.second > b.second || (a.second == b.second && a.first < b.first);
  });
  // The probes in rows from the first, as finish() spreads them: the lowest rows of a part meet
  // what lies on a sheet filled from its foot first.
  for (auto it = shape.probes.rbegin(); it != shape.probes.rend(); ++it)
    out.probes.emplace_back(w - 1 - it->first, h - 1 - it->second);
  for (auto it = shape.more_probes.rbegin(); it != shape.more_probes.rend(); ++it)
    out.more_probes.emplace_back(w - 1 - it->first, h - 1 - it->second);
  return out;
}

// Whether the mask moved to (x, y) meets a marked cell of the sheet. Row `meets` of the mask is
// compared first, and becomes the row where it meets one: the places beside and above a place
// that meets one mostly meet it there too.
bool collides(const Bits& sheet, const Bits& mask, int x, int y, int& meets) {
  const int first = x / 64, last = (x + mask.width() - 1) / 64;
  const int inner = x % 64;
  const auto row_meets = [&](int j) {
    for (int w = first; w <= last; ++w) {
      // The mask's row moved x cells right: its word w - x / 64, shifted by x % 64.
      const std::uint64_t m = mask.shifted(j, w - first, inner);
      if (m & sheet.word(y + j, w)) return true;
    }
    return false;
  };
  if (meets < mask.height() && row_meets(meets)) return true;
  for (int j = 0; j < mask.height(); ++j)
    if (j != meets && row_meets(j)) {
      meets = j;
      return true;
    }
  return false;
}

void stamp(Sheet& sheet, const Shape& shape, int x, int y) {
  const Bits& mask = shape.mask;
  const int first = x / 64, last = (x + mask.width() - 1) / 64;
  for (int j = 0; j < mask.height(); ++j) {
    for (int w = first; w <= last; ++w)
      sheet.cells.add(y + j, w, mask.shifted(j, w - first, x % 64));
    sheet.free_run[static_cast<std::size_t>(y + j)] = sheet.cells.longest_run(y + j, false);
  }
  sheet.update_most(y, y + mask.height());
  sheet.free -= shape.cells;
  find_tallest(sheet);
}

/// The lowest, then leftmost, place of `shape` on `sheet` where it touches nothing, no higher
/// than row `last_y`. A sheet with fewer free cells than the shape has, no free run as long as
/// its widest row, or fewer rows in a row with free runs as long as one of its bands needs
/// (Sheet::tallest), is passed over at once, and so are the rows up to the next where each of its
/// widest rows would lie on a row of the sheet with a free run as long (Sheet::next_row).
/// Sixty-four places of a row at a time are then ruled out where one of the shape's probes meets a
/// marked cell, then one of its more probes; the places left are compared cell by cell.
std::optional<std::pair<int, int>> lowest_place(const Sheet& on, const Shape& shape, int last_y) {
  const Bits& sheet = on.cells;
  const Bits& mask = shape.mask;
  if (shape.cells > on.free || shape.widest.empty() || shape.widest[0].second > on.widest_free())
    return std::nullopt;
  for (const Shape::Band& band : shape.bands)
    if (on.tallest[static_cast<std::size_t>(band.run)] < band.height) return std::nullopt;
  const int places = sheet.width() - mask.width() + 1;  // x in [0, places)
  std::size_t closer = 0;                               // the probe that closed the last places
  int meets = 0;  // the mask's row that met a marked cell last (collides)
  last_y = std::min(last_y, sheet.height() - mask.height());
  for (int y = 0; y <= last_y && places > 0; ++y) {
    // Up to the next row where each widest row has room, a widest row at a time: the rows
    // passed over have no free run as long under that one.
    bool room = true;
    for (const auto& [j, run] : shape.widest)
      if (on.free_run[static_cast<std::size_t>(y + j)] < run) {
        y = on.next_row(y + j, run) - j - 1;  // the loop's ++y then tries that row
        room = false;
        break;
      }
    if (!room) continue;
    for (int x0 = 0; x0 < places; x0 += 64) {
      std::uint64_t open =
          places - x0 >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << (places - x0)) - 1;
      // The probe that closed the last 64 places first: the places beside them, and those a row
      // up, mostly meet the same marked cells.
      if (closer < shape.probes.size()) {
        const auto [i, j] = shape.probes[closer];
        open &= ~sheet.from(y + j, x0 + i);
      }
      for (std::size_t k = 0; open != 0 && k < shape.probes.size(); ++k) {
        const auto [i, j] = shape.probes[k];
        open &= ~sheet.from(y + j, x0 + i);
        if (open == 0) closer = k;
      }
      for (std::size_t k = 0; open != 0 && k < shape.more_probes.size(); ++k) {
        const auto [i, j] = shape.more_probes[k];
        open &= ~sheet.from(y + j, x0 + i);
      }
      for (; open != 0; open &= open - 1) {
        const int x = x0 + std::countr_zero(open);
        if (!collides(sheet, mask, x, y, meets)) return std::pair{x, y};
      }
    }
  }
  return std::nullopt;
}

}  // namespace

std::vector<NestedOutline> nest_outlines(const std::vector<NestPart>& parts, std::int64_t grow,
                                         std::int64_t width, std::int64_t height) {
  const auto cols = static_cast<int>(width / kCell), rows = static_cast<int>(height / kCell);
  // Each part in its four quarter turns.
  std::vector<std::vector<Shape>> shapes(parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i)
    for (int q = 0; q < 4; ++q)
      shapes[i].push_back(q == 0   ? rasterise(parts[i], grow)
                          : q == 1 ? quarter_turned(shapes[i].back(), q * 0.5 * std::numbers::pi)
                                   : half_turned(shapes[i][q - 2], q * 0.5 * std::numbers::pi));
  // Parts placed in `order`, each on the first sheet where it fits; how many sheets it took.
  const auto fill = [&](const std::vector<std::size_t>& order, std::vector<NestedOutline>& out) {
    std::vector<Sheet> sheets;
    for (std::size_t i : order) {
      bool placed = false;
      for (std::size_t k = 0; k <= sheets.size() && !placed; ++k) {
        const bool fresh = k == sheets.size();
        if (fresh) sheets.emplace_back(cols, rows);
        // Of the turns that fit this sheet, the one that lies lowest, then leftmost.
        const Shape* best = nullptr;
        std::pair<int, int> at{0, 0};
        for (const Shape& s : shapes[i]) {
          if (s.mask.width() == 0) continue;
          // A turn placed no lower than the best so far is not wanted.
          const auto p = lowest_place(sheets[k], s, best ? at.second : rows);
          if (p && (!best || std::pair{p->second, p->first} < std::pair{at.second, at.first}))
            best = &s, at = *p;
        }
        if (!best && fresh) {
          sheets.pop_back();  // fits no sheet, not even an empty one
          break;
        }
        if (!best) continue;
        stamp(sheets[k], *best, at.first, at.second);
        out[i] = {static_cast<int>(k), best->angle, (at.first - best->ox) * kCell,
                  (at.second - best->oy) * kCell};
        placed = true;
      }
      if (placed) continue;
      // Too large for the grid's margin of cells: alone on a sheet, at its exact place, when its
      // box fits the sheet as it comes turned.
      std::int64_t lo_x = std::numeric_limits<std::int64_t>::max(), lo_y = lo_x;
      std::int64_t hi_x = std::numeric_limits<std::int64_t>::min(), hi_y = hi_x;
      for (const auto& polygon : parts[i])
        for (const IntPoint& p : polygon) {
          lo_x = std::min(lo_x, p.x - grow), hi_x = std::max(hi_x, p.x + grow);
          lo_y = std::min(lo_y, p.y - grow), hi_y = std::max(hi_y, p.y + grow);
        }
      if (lo_x > hi_x || hi_x - lo_x > width || hi_y - lo_y > height) continue;
      Sheet& full = sheets.emplace_back(cols, rows);
      for (int y = 0; y < rows; ++y) full.cells.set_span(0, cols - 1, y);
      std::fill(full.free_run.begin(), full.free_run.end(), 0);
      full.update_most(0, rows);
      full.free = 0;
      find_tallest(full);
      out[i] = {static_cast<int>(sheets.size()) - 1, 0, -lo_x, -lo_y};
    }
    return sheets.size();
  };
  // Largest first, by area, by the longest side, by the box: the order that takes the fewest
  // sheets (the first of them on a tie).
  const auto by = [&](auto key) {
    std::vector<std::size_t> order(parts.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return key(a) > key(b); });
    return order;
  };
  const auto& turns = shapes;
  const std::vector<std::vector<std::size_t>> orders{
      by([&](std::size_t i) { return turns[i][0].area; }),
      by([&](std::size_t i) {
        return static_cast<double>(std::max(turns[i][0].mask.width(), turns[i][0].mask.height()));
      }),
      by([&](std::size_t i) {
        return static_cast<double>(turns[i][0].mask.width()) * turns[i][0].mask.height();
      }),
  };
  std::vector<NestedOutline> out;
  std::vector<std::size_t> best;
  std::size_t fewest = std::numeric_limits<std::size_t>::max();
  const auto keep_if_fewer = [&](const std::vector<std::size_t>& order) {
    std::vector<NestedOutline> tried(parts.size());
    const std::size_t sheets = fill(order, tried);
    if (sheets >= fewest) return false;
    fewest = sheets, out = std::move(tried), best = order;
    return true;
  };
  for (const auto& order : orders) keep_if_fewer(order);
  // Then the parts the best order left on its last sheet go first, the others after them in the
  // same order: a long part placed late finds no room left on the sheets before, where placed
  // early it does (thingi10k 1063852 at 1,000 faces: 6 sheets became 5). Kept when that takes
  // fewer sheets, and tried again from there.
  for (int round = 0; round < kLastSheetRounds && fewest > 1; ++round) {
    const auto last = static_cast<int>(fewest) - 1;
    std::vector<std::size_t> order = best;
    std::stable_partition(order.begin(), order.end(),
                          [&](std::size_t i) { return out[i].sheet == last; });
    if (!keep_if_fewer(order)) break;
  }
  return out;
}

}  // namespace papernet::print_detail
