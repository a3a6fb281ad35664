#include "print/internal/piece_labels.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "print/tabs.h"

namespace papernet::print_detail {
namespace {

constexpr double kLargestMm = 8;         // a piece's number, at most
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

/// How far `p` lies from the convex polygon `box` (counter-clockwise): 0 inside it.
double distance_to_box(Vec2 p, const std::array<Vec2, 4>& box) {
  bool inside = true;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < box.size(); ++k) {
    const Vec2 a = box[k], b = box[(k + 1) % box.size()];
    inside = inside && cross(b - a, p - a) >= 0;
    const Vec2 ab = b - a;
    const double len2 = dot(ab, ab);
    const double t = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    nearest = std::min(nearest, norm(p - (a + t * ab)));
  }
  return inside ? 0.0 : nearest;
}

/// How far `p` lies from the axis-aligned box `bounds`: at most how far it lies from anything
/// inside it.
double distance_to_bounds(Vec2 p, const Box2& bounds) {
  const double dx = std::max({bounds.lo.x - p.x, p.x - bounds.hi.x, 0.0});
  const double dy = std::max({bounds.lo.y - p.y, p.y - bounds.hi.y, 0.0});
  return std::sqrt(dx * dx + dy * dy);
}

/// How far `p`, inside triangle `t`, lies from its sides.
double distance_to_sides(Vec2 p, const std::array<Vec2, 3>& t) {
  double nearest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const Vec2 a = t[k], b = t[(k + 1) % 3];
    const double len = norm(b - a);
    if (!(len > 0)) return 0;
    nearest = std::min(nearest, std::abs(cross(b - a, p - a)) / len);
  }
  return nearest;
}

}  // namespace

std::vector<Label> place_piece_labels(const std::vector<std::array<Vec2, 3>>& faces,
                                      const std::vector<Label>& labels,
                                      const std::vector<Segment>& leaders,
                                      const std::vector<int>& piece) {
  int count = 0;
  for (int p : piece) count = std::max(count, p + 1);
  std::vector<std::vector<int>> faces_of(static_cast<std::size_t>(count));
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) faces_of[piece[f]].push_back(f);
  // The edge labels' and leaders' boxes, by piece, each with its axis-aligned bounds.
  struct Clear {
    std::array<Vec2, 4> box;
    Box2 bounds;
  };
  std::vector<std::vector<Clear>> boxes(faces_of.size());
  const auto keep_clear = [&](int p, const std::array<Vec2, 4>& box) {
    Box2 bounds = Box2::empty();
    for (Vec2 q : box) bounds.add(q);
    boxes[p].push_back({box, bounds});
  };
  for (const Label& l : labels)
    if (!l.text.empty() && l.size > 0) keep_clear(piece[l.side.face], label_box(l));
  for (const Segment& s : leaders)
    if (s.face >= 0 && norm(s.b - s.a) > 0) keep_clear(piece[s.face], leader_box(s.a, s.b));
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
    // face; so the number can be turned to read level on the page (angle 0 here, and wherever
    // nesting or tiling moves the piece). Each face is tried at the centre of its inscribed
    // circle and at points towards its corners and the middles of its sides, where the labels
    // of its edges may leave room that the centre has not; the largest number wins.
    const double c = label_chars(label.text);
    const double diagonal = std::sqrt(0.09 * c * c + 0.25);
    label.angle = 0;
    // How far `at` lies from the nearest box, where that is nearer than `within` (infinity:
    // wherever it is); else a distance at least `within`. Boxes whose bounds lie farther are
    // passed over.
    const auto clear_of_boxes = [&](Vec2 at, double within) {
      double clear = std::numeric_limits<double>::infinity();
      for (const Clear& b : boxes[p])
        if (distance_to_bounds(at, b.bounds) <= within * (1 + 1e-9) + 1e-12)
          clear = std::min(clear, distance_to_box(at, b.box));
      return clear;
    };
    const auto each_place = [&](auto&& visit) {
      for (const int f : candidates) {
        const auto& t = faces[f];
        const Vec2 centre = circle[f].centre;
        std::array<Vec2, 10> points;
        points[0] = centre;
        for (int k = 0; k < 3; ++k) {
          points[1 + k] = centre + 0.3 * (t[k] - centre);
          points[4 + k] = centre + 0.6 * (t[k] - centre);
          points[7 + k] = centre + 0.6 * (0.5 * (t[k] + t[(k + 1) % 3]) - centre);
        }
        for (const Vec2 at : points) visit(f, at);
      }
    };
    double best_size = -1;
    Vec2 best_at{};
    int best_face = -1;
    each_place([&](int f, Vec2 at) {
      // As large as the face holds (its disc within 0.9 of the room to the face's sides), at most
      // kLargestMm, with its disc clear of the edge labels by kLabelGap of its size: boxes
      // farther than that size allows do not limit it.
      const double held = std::min(kLargestMm, 0.9 * distance_to_sides(at, faces[f]) / diagonal);
      const double within = held * (diagonal + kLabelGap);
      const double size = std::min(held, clear_of_boxes(at, within) / (diagonal + kLabelGap));
      if (size > best_size) best_size = size, best_at = at, best_face = f;
    });
    double best_clear = -1;
    Vec2 clearest_at{};
    int clearest_face = -1;
    if (!(best_face >= 0 && best_size >= kLegibleLabelMm))
      each_place([&](int f, Vec2 at) {
        const double clear = clear_of_boxes(at, std::numeric_limits<double>::infinity());
        if (clear > best_clear) best_clear = clear, clearest_at = at, clearest_face = f;
      });
    if (best_face >= 0 && best_size >= kLegibleLabelMm) {
      label.at = best_at;
      label.side = {best_face, 0};
      label.size = best_size;
    } else if (clearest_face >= 0) {
      // No place holds it legibly clear of the edge labels: at the legible size where it meets
      // them least, farthest from them.
      label.at = clearest_at;
      label.side = {clearest_face, 0};
      label.size = kLegibleLabelMm;
    }
    out.push_back(std::move(label));
  }
  return out;
}

}  // namespace papernet::print_detail
