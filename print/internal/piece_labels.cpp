#include "print/internal/piece_labels.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "print/tabs.h"

namespace papernet::print_detail {
namespace {

constexpr double kLargestMm = 8;         // a piece's number, at most
constexpr double kWantedMm = 3;          // and at least, where a face holds it
constexpr std::size_t kFacesTried = 40;  // per piece, by inscribed circle

struct Circle {
  Vec2 centre;
  double radius = 0;
};

Circle incircle(const std::array<Vec2, 3>& t) {
  const double a = norm(t[1] - t[2]), b = norm(t[2] - t[0]), c = norm(t[0] - t[1]);
  const double perimeter = a + b + c;
  if (!(perimeter > 0)) return {t[0], 0};
  const Vec2 centre = (1 / perimeter) * (a * t[0] + b * t[1] + c * t[2]);
  const double area = 0.5 * std::abs(cross(t[1] - t[0], t[2] - t[0]));
  return {centre, 2 * area / perimeter};
}

}  // namespace

std::vector<Label> place_piece_labels(const std::vector<std::array<Vec2, 3>>& faces,
                                      const std::vector<Label>& labels,
                                      const std::vector<int>& piece) {
  int count = 0;
  for (int p : piece) count = std::max(count, p + 1);
  std::vector<std::vector<int>> faces_of(static_cast<std::size_t>(count));
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) faces_of[piece[f]].push_back(f);
  std::vector<std::vector<std::array<Vec2, 4>>> boxes(faces_of.size());  // edge labels by piece
  for (const Label& l : labels)
    if (!l.text.empty() && l.size > 0) boxes[piece[l.side.face]].push_back(label_box(l));
  std::vector<Circle> circle(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) circle[f] = incircle(faces[f]);
  std::vector<Label> out;
  for (int p = 0; p < count; ++p) {
    Label label;
    label.text = piece_name(p);
    std::vector<int>& candidates = faces_of[p];
    std::sort(candidates.begin(), candidates.end(), [&](int a, int b) {
      return circle[a].radius > circle[b].radius || (circle[a].radius == circle[b].radius && a < b);
    });
    if (candidates.size() > kFacesTried) candidates.resize(kFacesTried);
    // The box's half-diagonal over its height: the box fits the circle when size * this <= r.
    const double c = label_chars(label.text);
    const double diagonal = std::sqrt(0.09 * c * c + 0.25);
    bool placed = false;
    for (const double least : {kWantedMm, kLegibleLabelMm}) {
      for (std::size_t i = 0; i < candidates.size() && !placed; ++i) {
        const int f = candidates[i];
        const auto& t = faces[f];
        int longest = 0;
        for (int k = 1; k < 3; ++k)
          if (norm(t[(k + 1) % 3] - t[k]) > norm(t[(longest + 1) % 3] - t[longest])) longest = k;
        const Vec2 d = t[(longest + 1) % 3] - t[longest];
        label.angle = std::atan2(d.y, d.x);
        if (std::cos(label.angle) < -1e-9) label.angle += std::numbers::pi;
        label.at = circle[f].centre;
        label.side = {f, 0};
        for (label.size = std::min(kLargestMm, 0.9 * circle[f].radius / diagonal);
             label.size >= least && !placed; label.size *= 0.85) {
          const auto box = label_box(label);
          placed = std::none_of(boxes[p].begin(), boxes[p].end(),
                                [&](const auto& other) { return convex_overlap(box, other, 0); });
          if (placed) break;
        }
      }
      if (placed) break;
    }
    if (!placed && !candidates.empty()) {
      // Nothing clear: the widest face, as large as it holds (over an edge label).
      const int f = candidates.front();
      label.at = circle[f].centre;
      label.side = {f, 0};
      label.angle = 0;
      label.size = std::max(kLegibleLabelMm, circle[f].radius / diagonal);
    }
    out.push_back(std::move(label));
  }
  return out;
}

}  // namespace papernet::print_detail
