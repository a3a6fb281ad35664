#include "print/internal/label_leaders.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <queue>
#include <unordered_map>
#include <utility>

namespace papernet::print_detail {
namespace {

// Labels under the legible size beyond which none is placed away from its edge: a mesh that
// dense (the rocker arm with every face kept: 4,600) has no room for them, and trying took 2 s.
constexpr std::size_t kMostFarLabels = 200;

// How far over its piece's folds a leader routed over the faces reaches from its edge, mm, and
// of how many lines it is at most (place_far_labels).
constexpr double kRouteMm = 15;
constexpr std::size_t kMostRouteLines = 4;
// What a leader's bend costs against its length, mm: a line of two parts wins over a straight
// one only when it is that much shorter.
constexpr double kRouteBendMm = 3;
// How many places beside its edge a small label tries whose one label in the way moves away
// with a leader, and how many of all a layout's small labels try (place_far_labels, make_way):
// each try is the rings' search for that label.
constexpr std::size_t kMostWayLeaders = 8;
constexpr std::size_t kMostWayLeadersInAll = 96;
constexpr std::size_t kMostSmallForWayLeaders = 40;

}  // namespace

std::vector<Segment> place_far_labels(const std::vector<std::array<Vec2, 3>>& faces,
                                      const PaperGrid& grid, std::vector<Label>& labels,
                                      const LabelClock& clock) {
  std::vector<Segment> leaders;
  const auto small =
      static_cast<std::size_t>(std::count_if(labels.begin(), labels.end(), [](const Label& l) {
        return !l.text.empty() && l.size < kLegibleLabelMm;
      }));
  if (small == 0 || small > kMostFarLabels) return leaders;
  LabelBoxes boxes(labels);
  // The leaders' boxes, each with the box around it (which rules out most pairs sooner).
  std::vector<std::pair<Box2, std::array<Vec2, 4>>> drawn;
  const auto meets_drawn = [&](const std::array<Vec2, 4>& quad) {
    const Box2 b = box_around(quad);
    return std::any_of(drawn.begin(), drawn.end(),
                       [&](const auto& l) { return quads_meet(quad, b, l.second, l.first); });
  };
  std::vector<char> led(labels.size(), 0);  // the labels placed here with a leader
  // Label `i` printed at kLegibleLabelMm away from its edge with a leader line, in the rounds
  // the function's comment gives; true when it found a place.
  const auto lead_away = [&](int i, bool routed) {
    const Label& label = labels[i];
    const int face = label.side.face;
    const auto& tri = faces[face];
    const Vec2 p0 = tri[label.side.k], p1 = tri[(label.side.k + 1) % 3];
    const Vec2 p2 = tri[(label.side.k + 2) % 3];
    const double len = norm(p1 - p0);
    if (!(len > 0)) return false;
    const Vec2 d = (1 / len) * (p1 - p0), middle = 0.5 * (p0 + p1);
    Vec2 up{-d.y, d.x};
    if (dot(p2 - middle, up) < 0) up = Vec2{0, 0} - up;
    Label far = label;
    far.size = kLegibleLabelMm;
    const double half_w = 0.3 * far.size * label_chars(far.text), half_h = 0.5 * far.size;
    Segment leader, bend;  // bend.face: -1 for a straight leader
    bool bent = false;     // the second round: leaders that bend (the first tried straight ones)
    // True when a leader may run from `a` to `b` (`b` on the edge when `to_edge`): it starts on
    // the piece and crosses no cut line (it stops 0.05 mm short of its own edge for the test),
    // so it runs over the piece; its middle is on the piece, so it reaches its edge from the
    // face's side; it meets no other label and no leader drawn before.
    const auto clear = [&](Vec2 a, Vec2 b, bool to_edge) {
      const double reach = norm(b - a);
      if (reach <= 0.1) return true;
      const std::array<Vec2, 2> line{a,
                                     to_edge ? a + std::max(0.0, 1 - 0.05 / reach) * (b - a) : b};
      const std::array<Vec2, 4> box = leader_box(a, b);
      return grid.on_piece(a, face) && grid.on_piece(0.5 * (a + b), face) &&
             !grid.meets_cut(line) && !boxes.meets(box, i) && !meets_drawn(box);
    };
    // True when the label fits at `at`, turned `angle`, with its leader (into `leader`, and
    // `bend`).
    const auto fits = [&](Vec2 at, double angle) {
      far.at = at;
      far.angle = angle;
      turn_upright(far);
      if (!grid.on_piece(at, face)) return false;  // the cheapest test first
      const std::array<Vec2, 4> box = label_box(far);
      if (boxes.meets(box, i) || !box_on_piece(grid, box, face)) return false;
      if (meets_drawn(box)) return false;
      // From the box's point nearest the edge's middle to the edge's point nearest that, else
      // to other points of the edge's middle three fifths (it points at one edge, not at a
      // corner of several).
      const Vec2 along{std::cos(far.angle), std::sin(far.angle)}, across{-along.y, along.x};
      const Vec2 rel = middle - at;
      const Vec2 q = at + std::clamp(dot(rel, along), -half_w, half_w) * along +
                     std::clamp(dot(rel, across), -half_h, half_h) * across;
      const double nearest = std::clamp(dot(q - p0, d) / len, 0.2, 0.8);
      bend.face = -1;
      if (!bent) {
        for (const double part : {nearest, 0.5, 0.35, 0.65, 0.2, 0.8}) {
          const Vec2 m = p0 + (part * len) * d;
          if (!clear(q, m, true)) continue;
          leader = {q, m, face};
          return true;
        }
        return false;
      }
      // On the second round, with a bend in front of the edge's middle (1 to 3 mm from it,
      // straight or at 30 or 60 degrees), round a cut line that the straight one crosses: the
      // straight leaders were tried at this place on the first round, nothing has changed
      // since, and none was clear.
      for (const double r : {1.0, 2.0, 3.0})
        for (const double turn : {0.0, 1.0, -1.0, 2.0, -2.0}) {
          const double a = turn * std::numbers::pi / 6;
          const Vec2 k = middle + r * (std::cos(a) * up + std::sin(a) * d);
          if (!grid.on_piece(k, face) || !clear(k, middle, true) || !clear(q, k, false)) continue;
          leader = {q, k, face};
          bend = {k, middle, face};
          return true;
        }
      return false;
    };
    const double along_edge = std::atan2(d.y, d.x);
    // The third round, where neither found a place: a leader of up to kMostRouteLines lines
    // over the faces of the piece, to a place on a face that the edge's face reaches across its
    // folds within kRouteMm (a short cut edge deep in a notch, whose straight and bent leaders
    // all cross a cut line). A path runs from a point of the edge's middle three fifths through
    // points of the folds crossed (at 0.2 to 0.8 of each) and points inside the faces near their
    // corners, each line of it inside one face (so on the piece) and clear (as above); from the
    // label's box to where it enters the label's face, it is pulled straight where a line from a
    // point to a later one is clear. Of the places on the faces reached, the one whose leader is
    // shortest wins, each line after the first counted kRouteBendMm longer. Into `label` and
    // `route`.
    const auto route_over_piece = [&](int self, Label& label, std::vector<Segment>& route) {
      // Where a leader crosses a side: at these fractions of it.
      constexpr std::array<double, 5> kCrossings{0.5, 0.35, 0.65, 0.2, 0.8};
      struct Reached {
        int face, from;     // from: the index of the point before (-1: the path's first, on the
                            // edge)
        Vec2 at;            // where the path enters the face
        double length;      // of the path from the edge
        std::uint64_t key;  // the faces on either side of the side crossed there, and the point
      };
      std::vector<Reached> reached;
      using Entry = std::pair<double, int>;  // path length, index into `reached`
      std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
      for (const double part : kCrossings) {
        reached.push_back({face, -1, p0 + (part * len) * d, 0, ~std::uint64_t{0}});
        open.push({0.0, static_cast<int>(reached.size()) - 1});
      }
      std::unordered_map<std::uint64_t, double> best;     // the shortest path to each point
      std::unordered_map<int, std::vector<int>> entries;  // each face's points, nearest first
      std::vector<int> order;                             // the faces, nearest first
      while (!open.empty()) {
        // Not a structured binding: step (a lambda) uses both, which clang 14 does not allow.
        const double length = open.top().first;
        const int r = open.top().second;
        open.pop();
        const Reached here = reached[r];
        if (here.from >= 0 && length > best[here.key]) continue;  // reached shorter since
        std::vector<int>& in = entries[here.face];
        if (in.empty()) order.push_back(here.face);
        in.push_back(r);
        const auto step = [&](int into, Vec2 at, std::uint64_t key) {
          const double to = length + norm(at - here.at);
          if (to > kRouteMm) return;
          if (const auto it = best.find(key); it != best.end() && it->second <= to) return;
          if (!clear(at, here.at, here.from < 0)) return;
          best[key] = to;
          reached.push_back({into, r, at, to, key});
          open.push({to, static_cast<int>(reached.size()) - 1});
        };
        for (const PaperGrid::Fold& fold : grid.folds(here.face))
          for (std::uint64_t c = 0; c < kCrossings.size(); ++c)
            step(fold.face, fold.a + kCrossings[c] * (fold.b - fold.a),
                 (static_cast<std::uint64_t>(fold.face) << 35) |
                     (static_cast<std::uint64_t>(here.face) << 4) | c);
        const auto& t = faces[here.face];
        for (std::uint64_t k = 0; k < 3; ++k)
          step(here.face, (4.0 / 6) * t[k] + (1.0 / 6) * (t[(k + 1) % 3] + t[(k + 2) % 3]),
               (static_cast<std::uint64_t>(here.face) << 35) |
                   (static_cast<std::uint64_t>(here.face) << 4) | (8 + k));
      }
      // Each point's leader to the edge, pulled straight: a line to the farthest point of its
      // path with a clear line (the point before it at least: the path's lines are clear), and
      // on from there. Worked out when first wanted.
      struct Pulled {
        int lines = -1;  // -1: not worked out yet
        double score = 0;
        int to = -1;  // the point the first line runs to (-1: on the edge, no line)
      };
      std::vector<Pulled> pulled(reached.size());
      const auto pull = [&](const auto& self_ref, int x) -> const Pulled& {
        Pulled& out = pulled[x];
        if (out.lines >= 0) return out;
        out = {0, 0, -1};
        if (reached[x].from < 0) return out;
        std::vector<int> up;  // the points before it, back to the edge
        for (int p = reached[x].from; p >= 0; p = reached[p].from) up.push_back(p);
        for (std::size_t j = up.size(); j-- > 0;) {
          const int n = up[j];
          if (j > 0 && !clear(reached[x].at, reached[n].at, reached[n].from < 0)) continue;
          const Pulled& rest = self_ref(self_ref, n);
          pulled[x] = {rest.lines + 1,
                       norm(reached[n].at - reached[x].at) + rest.score +
                           (rest.lines > 0 ? kRouteBendMm : 0),
                       n};
          break;
        }
        return pulled[x];
      };
      double best_score = INFINITY;
      Label best_label;
      int best_first = -1;  // the point of the path the best leader's first line runs to
      Vec2 best_start;      // where it leaves the label's box
      for (const int g : order) {
        if (g == face) continue;
        // Nearest face first, until the path to a face is longer than the best leader found.
        if (reached[entries[g].front()].length >= best_score) break;
        const auto& t = faces[g];
        const Vec2 c = (1.0 / 3) * (t[0] + t[1] + t[2]);
        int longest = 0;
        for (int k = 1; k < 3; ++k)
          if (norm(t[(k + 1) % 3] - t[k]) > norm(t[(longest + 1) % 3] - t[longest])) longest = k;
        const Vec2 side = t[(longest + 1) % 3] - t[longest];
        // Places over the face: its centroid, and the points of a grid of sixths of it.
        std::vector<Vec2> places{c};
        for (int u = 1; u < 6; ++u)
          for (int v = 1; u + v < 6; ++v)
            if (u != 2 || v != 2)
              places.push_back((u / 6.0) * t[0] + (v / 6.0) * t[1] + ((6 - u - v) / 6.0) * t[2]);
        for (const Vec2 at : places)
          for (const double angle :
               {along_edge, 0.0, std::atan2(side.y, side.x), along_edge + std::numbers::pi / 2}) {
            label.at = at;
            label.angle = angle;
            turn_upright(label);
            if (!grid.on_piece(at, face)) continue;
            const std::array<Vec2, 4> box = label_box(label);
            if (boxes.meets(box, self) || !box_on_piece(grid, box, face)) continue;
            if (meets_drawn(box)) continue;
            // The box's point nearest `p`.
            const Vec2 along{std::cos(label.angle), std::sin(label.angle)};
            const Vec2 across{-along.y, along.x};
            const auto nearest = [&](Vec2 p) {
              return label.at + std::clamp(dot(p - label.at, along), -half_w, half_w) * along +
                     std::clamp(dot(p - label.at, across), -half_h, half_h) * across;
            };
            for (const int r : entries[g]) {
              if (reached[r].length >= best_score) break;
              // The first line: from the box to the farthest point of the path (from where it
              // enters this face back to the edge) with a clear line.
              std::vector<int> path;
              for (int p = r; p >= 0; p = reached[p].from) path.push_back(p);
              for (std::size_t j = path.size(); j-- > 0;) {
                const int n = path[j];
                const Vec2 start = nearest(reached[n].at);
                if (norm(reached[n].at - start) < 1e-9) continue;
                if (!clear(start, reached[n].at, reached[n].from < 0)) continue;
                const Pulled& rest = pull(pull, n);
                const double score =
                    norm(reached[n].at - start) + rest.score + (rest.lines > 0 ? kRouteBendMm : 0);
                if (rest.lines + 1 <= static_cast<int>(kMostRouteLines) && score < best_score) {
                  best_score = score;
                  best_label = label;
                  best_first = n;
                  best_start = start;
                }
                break;
              }
            }
          }
      }
      if (best_score > kRouteMm) return false;
      label = best_label;
      route = {{best_start, reached[best_first].at, face}};
      for (int n = best_first; pulled[n].to >= 0; n = pulled[n].to)
        route.push_back({reached[n].at, reached[pulled[n].to].at, face});
      return true;
    };
    bool placed = false;
    for (const bool with_bend : {false, true}) {
      bent = with_bend;
      for (const double r : {2.0, 3.0, 4.0, 5.5, 7.0, 9.0, 11.5, 15.0}) {
        for (int j = 0; j <= 12 && !placed; ++j)
          for (const int sign : {1, -1}) {
            if ((j == 0 || j == 12) && sign < 0) continue;
            const double turn = sign * j * std::numbers::pi / 12;
            const Vec2 at = middle + r * (std::cos(turn) * up + std::sin(turn) * d);
            if ((placed = fits(at, along_edge) || fits(at, 0) ||
                          fits(at, along_edge + std::numbers::pi / 2)))
              break;
          }
        if (placed) break;
      }
      if (placed) break;
    }
    std::vector<Segment> route{leader, bend};
    if (!placed && routed) placed = route_over_piece(i, far, route);
    if (!placed) return false;
    led[i] = 1;
    boxes.move(i, far);
    for (const Segment& s : route)
      if (s.face >= 0) {
        const std::array<Vec2, 4> box = leader_box(s.a, s.b);
        drawn.emplace_back(box_around(box), box);
        leaders.push_back(s);
      }
    return true;
  };

  // Tried before lead_away: a place beside the edge (as make_labels_legible tries them) that
  // one legible label without a leader takes, where that label has another place beside its own
  // edge, clear of every other, or else (for the first kMostWayLeaders such places of a label,
  // and kMostWayLeadersInAll of all) one away from its edge with a straight or bent leader
  // (ADIS16480 at the defaults: the label 96 of a 3 mm edge of a triangle in a notch, whose room
  // beside it the label `99.` across a fold reached over). Both move; true when they did.
  // Where many labels are small (a dense mesh with every face kept) they do not: each try is the
  // rings' search for the label in the way.
  std::size_t led_away_left = small <= kMostSmallForWayLeaders ? kMostWayLeadersInAll : 0;
  const auto make_way = [&](int i) {
    const Label before = labels[i];
    std::size_t away = kMostWayLeaders;  // the places left whose label in the way may move
                                         // away with a leader
    for (const Label& here : beside_places(faces, before)) {
      const std::array<Vec2, 4> box = label_box(here);
      if (!beside_on_piece(faces, grid, here, box) || meets_drawn(box)) continue;
      const std::vector<int> in_way = boxes.meeting(box, i);
      if (in_way.size() != 1) continue;
      const int j = in_way.front();
      if (labels[j].size < kLegibleLabelMm || led[j]) continue;
      boxes.move(i, here);
      for (const Label& there : beside_places(faces, labels[j])) {
        const std::array<Vec2, 4> other = label_box(there);
        if (boxes.meets(other, j) || !beside_on_piece(faces, grid, there, other) ||
            meets_drawn(other))
          continue;
        boxes.move(j, there);
        return true;
      }
      if (away > 0 && led_away_left > 0) {
        --away;
        --led_away_left;
        if (lead_away(j, false)) return true;
      }
      boxes.move(i, before);
    }
    return false;
  };
  for (const int i : smallest_first(labels)) {
    if (clock.out()) return leaders;
    const Label& label = labels[i];
    if (label.text.empty() || label.size >= kLegibleLabelMm) continue;
    if (!make_way(i)) lead_away(i, true);
  }
  // Once more for the labels still small: the labels moved away with a leader since left room.
  for (const int i : smallest_first(labels)) {
    if (clock.out()) break;
    if (!labels[i].text.empty() && labels[i].size < kLegibleLabelMm) make_way(i);
  }
  return leaders;
}

}  // namespace papernet::print_detail
