#include "print/arrange.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/unfold/net_metrics.h"

namespace papernet {

Net arrange_pieces(const Net& net, const std::vector<int>& piece, double gap) {
  const int pieces = piece.empty() ? 0 : *std::max_element(piece.begin(), piece.end()) + 1;
  if (pieces <= 1) return net;
  // Each piece turned into its minimum-area box, with its corner at the origin.
  std::vector<std::vector<Vec2>> points(pieces);
  for (std::size_t f = 0; f < net.points.size(); ++f)
    points[piece[f]].insert(points[piece[f]].end(), net.points[f].begin(), net.points[f].end());
  std::vector<OrientedBox> box(pieces);
  double area = 0, widest = 0;
  for (int p = 0; p < pieces; ++p) {
    box[p] = min_area_box(points[p]);
    area += (box[p].width() + gap) * (box[p].height() + gap);
    widest = std::max(widest, box[p].width());
  }
  // Rows of pieces, tallest first, as wide as an A-series sheet's proportion gives.
  const double row_width = std::max(widest, std::sqrt(area * std::sqrt(2.0)));
  std::vector<int> order(pieces);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return box[a].height() > box[b].height(); });
  std::vector<Vec2> offset(pieces);
  double x = 0, y = 0, row_height = 0;
  for (int p : order) {
    if (x > 0 && x + box[p].width() > row_width) {
      x = 0;
      y += row_height + gap;
      row_height = 0;
    }
    offset[p] = Vec2{x, y} - box[p].lo;
    x += box[p].width() + gap;
    row_height = std::max(row_height, box[p].height());
  }
  Net out = net;
  for (std::size_t f = 0; f < out.points.size(); ++f)
    for (Vec2& q : out.points[f]) q = rotate(q, box[piece[f]].angle) + offset[piece[f]];
  return out;
}

}  // namespace papernet
