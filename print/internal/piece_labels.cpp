#include "print/internal/piece_labels.h"

#include <algorithm>
#include <cmath>

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

/// True when the disc of `radius` about `centre` meets the convex polygon `box`.
bool disc_meets(Vec2 centre, double radius, const std::array<Vec2, 4>& box) {
  bool inside = true;
  for (std::size_t k = 0; k < box.size(); ++k) {
    const Vec2 a = box[k], b = box[(k + 1) % box.size()];
    inside = inside && cross(b - a, centre - a) >= 0;
    const Vec2 ab = b - a;
    const double len2 = dot(ab, ab);
    const double t = len2 > 0 ? std::clamp(dot(centre - a, ab) / len2, 0.0, 1.0) : 0.0;
    if (norm(centre - (a + t * ab)) < radius) return true;
  }
  return inside;
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
    // The box's half-diagonal over its height: the box, at any turn about its centre, lies in
    // a disc of radius size * this, which must keep clear of the edge labels and inside the
    // face's inscribed circle; so the number can be turned to read level on the page (angle 0
    // here, and wherever nesting or tiling moves the piece).
    const double c = label_chars(label.text);
    const double diagonal = std::sqrt(0.09 * c * c + 0.25);
    label.angle = 0;
    bool placed = false;
    for (const double least : {kWantedMm, kLegibleLabelMm}) {
      for (std::size_t i = 0; i < candidates.size() && !placed; ++i) {
        const int f = candidates[i];
        label.at = circle[f].centre;
        label.side = {f, 0};
        for (label.size = std::min(kLargestMm, 0.9 * circle[f].radius / diagonal);
             label.size >= least; label.size *= 0.85) {
          const double reach = label.size * diagonal;
          placed = std::none_of(boxes[p].begin(), boxes[p].end(), [&](const auto& other) {
            return disc_meets(label.at, reach, other);
          });
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
      label.size = std::max(kLegibleLabelMm, circle[f].radius / diagonal);
    }
    out.push_back(std::move(label));
  }
  return out;
}

}  // namespace papernet::print_detail
