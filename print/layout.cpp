#include "print/layout.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <queue>
#include <span>
#include <unordered_map>

#include "core/errors.h"
#include "print/internal/grid_cells.h"
#include "print/internal/piece_labels.h"

namespace papernet {

std::string tab_mode_name(TabMode mode) {
  switch (mode) {
    case TabMode::Auto:
      return "auto";
    case TabMode::Strips:
      return "strips";
    case TabMode::None:
      return "none";
  }
  return "auto";
}

std::string fit_goal_name(FitGoal goal) { return goal == FitGoal::Pieces ? "pieces" : "sheets"; }

void PrintOptions::validate() const {
  const auto fail = [](const char* option, const std::string& message) {
    throw InvalidOptionException("option_out_of_range", option, message);
  };
  auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  if (!(scale > 0) && !positive(size_mm)) fail("size_mm", "size must be a positive length");
  if (!std::isfinite(scale) || scale < 0) fail("scale", "scale must be a positive factor");
  if (!std::isfinite(flat_fold_degrees) || flat_fold_degrees < 0 || flat_fold_degrees > 180)
    fail("flat_fold_degrees", "flat fold angle must be between 0 and 180 degrees");
  if (!std::isfinite(tab_height_mm) || tab_height_mm < 0)
    fail("tab_height_mm", "tab height must be >= 0");
  if (!(tab_angle_deg > 0 && tab_angle_deg <= 90))
    fail("tab_angle_deg", "tab angle must be in (0, 90] degrees");
  if (!std::isfinite(min_tab_height_mm) || min_tab_height_mm < 0)
    fail("min_tab_height_mm", "minimum tab height must be >= 0");
  if (!positive(max_label_mm)) fail("max_label_mm", "label size must be positive");
  if (tab_room_budget > kMaxTabRoomBudget)
    fail("tab_room_budget",
         "tab room budget must be at most " + std::to_string(kMaxTabRoomBudget) + " moves");
  if (merge_budget > kMaxMergeBudget)
    fail("merge_budget",
         "merge budget must be at most " + std::to_string(kMaxMergeBudget) + " tests");
}

double label_chars(const std::string& text) {
  double width = 0;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x80)
      width += 1;
    else if (byte >= 0xC0)  // the first byte of a multi-byte character
      width += 1.4;
  }
  return width;
}

double text_width(const std::string& text, double size) { return 0.6 * size * label_chars(text); }

std::string piece_name(int piece) {
  std::string name = "P";
  name += std::to_string(piece + 1);
  return name;
}

std::array<Vec2, 4> label_box(const Label& label) {
  const Vec2 d{std::cos(label.angle), std::sin(label.angle)}, up{-d.y, d.x};
  const double hw = 0.3 * label.size * label_chars(label.text);
  const double hh = 0.5 * label.size;
  return {label.at - hw * d - hh * up, label.at + hw * d - hh * up, label.at + hw * d + hh * up,
          label.at - hw * d + hh * up};
}

std::array<Vec2, 4> leader_box(Vec2 a, Vec2 b) {
  const double len = norm(b - a);
  const Vec2 d = len > 0 ? (1 / len) * (b - a) : Vec2{1, 0}, up{-0.1 * d.y, 0.1 * d.x};
  const Vec2 s = a + 0.05 * d, e = b - 0.05 * d;
  return {s - up, e - up, e + up, s + up};
}

LabelSizes label_sizes(const PrintLayout& layout) {
  LabelSizes out;
  const auto add = [&out](double size) {
    out.smallest_mm = out.count == 0 ? size : std::min(out.smallest_mm, size);
    ++out.count;
    out.illegible += size < kLegibleLabelMm;
  };
  for (const Label& l : layout.labels)
    if (!l.text.empty()) add(l.size);
  for (const GlueStrip& s : layout.strips)
    if (!s.text.empty()) add(s.text_size);
  return out;
}

namespace {

/// Text turned half a turn when it would read upside down (its box stays the same).
void turn_upright(Label& label) {
  if (std::cos(label.angle) < -1e-9) label.angle += std::numbers::pi;
}

/// The label for `side`, sized to fit the face: text along the edge, inside the triangle.
Label make_label(const std::array<Vec2, 3>& tri, EdgeSide side, std::string text, double max_size) {
  const Vec2 p0 = tri[side.k], p1 = tri[(side.k + 1) % 3], p2 = tri[(side.k + 2) % 3];
  const double len = norm(p1 - p0);
  const Vec2 d = len > 0 ? (1 / len) * (p1 - p0) : Vec2{1, 0}, up{-d.y, d.x};
  const double ht = dot(p2 - p0, up), a2 = dot(p2 - p0, d);  // apex height and offset
  const double chars = label_chars(text);
  if (!(len > 0 && ht > 0))  // a degenerate face: an empty label at its centroid
    return {(1.0 / 3) * (p0 + p1 + p2), 0, 0, std::move(text), -1, side};
  Label label{{}, std::atan2(d.y, d.x), std::min(max_size, 0.3 * ht), std::move(text), -1, side};
  for (int i = 0; i < 40; ++i, label.size *= 0.85) {
    const double s = label.size;
    const double lo = 0.08 * ht + 0.1 * s, hi = lo + s;  // the text box's distance from the edge
    // Cross-section of the triangle between heights lo and hi, along d.
    const double left_lo = lo / ht * a2, left_hi = hi / ht * a2;
    const double right_lo = len + lo / ht * (a2 - len), right_hi = len + hi / ht * (a2 - len);
    const double l = std::max(left_lo, left_hi), r = std::min(right_lo, right_hi);
    const double width = 0.6 * s * chars;
    if (r - l >= 1.15 * width || i == 39) {
      label.at = p0 + (0.5 * (l + r)) * d + (0.5 * (lo + hi)) * up;
      break;
    }
  }
  // Read upright on the page where possible: turning the text half a turn keeps its box.
  turn_upright(label);
  return label;
}

/// Places and sizes every label; labels that share a face shrink together until they are apart
/// by kLabelGap.
void size_labels(const std::vector<std::array<Vec2, 3>>& faces, std::vector<Label>& labels,
                 double max_size) {
  std::vector<std::vector<int>> by_face(faces.size());
  for (int i = 0; i < static_cast<int>(labels.size()); ++i)
    by_face[labels[i].side.face].push_back(i);
  for (const std::vector<int>& group : by_face) {
    double cap = max_size;
    for (int attempt = 0; attempt < 30; ++attempt, cap *= 0.8) {
      for (int i : group) {
        Label placed = make_label(faces[labels[i].side.face], labels[i].side, labels[i].text, cap);
        placed.edge = labels[i].edge;
        labels[i] = std::move(placed);
      }
      bool apart = true;
      for (std::size_t a = 0; a < group.size() && apart; ++a)
        for (std::size_t b = a + 1; b < group.size() && apart; ++b) {
          const Label& la = labels[group[a]];
          const Label& lb = labels[group[b]];
          apart = !convex_overlap(label_box(la), label_box(lb),
                                  -kLabelGap * std::min(la.size, lb.size));
        }
      if (apart) break;
    }
  }
}

/// The axis-aligned box around a quadrilateral (a label's box, a leader's).
Box2 box_around(const std::array<Vec2, 4>& quad) {
  Box2 b = Box2::empty();
  for (const Vec2 p : quad) b.add(p);
  return b;
}

/// True when two quadrilaterals overlap, each given with the box around it (which rules out most
/// pairs sooner).
bool quads_meet(const std::array<Vec2, 4>& a, const Box2& a_around, const std::array<Vec2, 4>& b,
                const Box2& b_around) {
  return a_around.lo.x <= b_around.hi.x && b_around.lo.x <= a_around.hi.x &&
         a_around.lo.y <= b_around.hi.y && b_around.lo.y <= a_around.hi.y &&
         convex_overlap(a, b, 0);
}

/// The boxes of a net's labels on a grid of cells, as the labels move: which other label a box
/// meets, on any face (a label moved beside its edge reaches over folds into other faces).
class LabelBoxes {
 public:
  explicit LabelBoxes(std::vector<Label>& labels) : labels_(labels), kept_(labels.size()) {
    for (int i = 0; i < static_cast<int>(labels.size()); ++i) add(i);
  }
  /// True when `label`'s box meets the box of a label other than label `self`.
  bool collides(const Label& label, int self) const { return meets(label_box(label), self); }
  /// True when `box` meets the box of a label other than label `self`.
  bool meets(const std::array<Vec2, 4>& box, int self) const {
    bool hit = false;
    const Box2 around = box_around(box);
    for_cells(box, [&](std::uint64_t key) {
      const auto it = cells_.find(key);
      if (hit || it == cells_.end()) return;
      for (const int j : it->second)
        if (j != self && overlaps(box, around, j)) {
          hit = true;
          return;
        }
    });
    return hit;
  }
  /// The labels other than label `self` whose boxes `box` meets.
  std::vector<int> meeting(const std::array<Vec2, 4>& box, int self) const {
    std::vector<int> out;
    const Box2 around = box_around(box);
    for_cells(box, [&](std::uint64_t key) {
      const auto it = cells_.find(key);
      if (it == cells_.end()) return;
      for (const int j : it->second)
        if (j != self && std::find(out.begin(), out.end(), j) == out.end() &&
            overlaps(box, around, j))
          out.push_back(j);
    });
    return out;
  }
  /// Label `i` moves to `to` (a place, size or angle of its own), its box with it.
  void move(int i, const Label& to) {
    remove(i);
    labels_[i] = to;
    add(i);
  }

 private:
  static constexpr double kCell = 4;  // mm: about a label's length
  // A label's box as added, and the box around it (which rules out most pairs sooner).
  struct Kept {
    std::array<Vec2, 4> box;
    Box2 around;
    bool in = false;
  };
  void remove(int i) {
    Kept& kept = kept_[i];
    if (!kept.in) return;
    kept.in = false;
    for_cells(kept.box, [&](std::uint64_t key) {
      std::vector<int>& in = cells_[key];
      in.erase(std::remove(in.begin(), in.end(), i), in.end());
    });
  }
  void add(int i) {
    if (labels_[i].text.empty()) return;
    remove(i);
    Kept& kept = kept_[i];
    kept = {label_box(labels_[i]), {}, true};
    kept.around = box_around(kept.box);
    for_cells(kept.box, [&](std::uint64_t key) { cells_[key].push_back(i); });
  }
  bool overlaps(const std::array<Vec2, 4>& box, const Box2& around, int j) const {
    if (labels_[j].text.empty()) return false;
    return quads_meet(box, around, kept_[j].box, kept_[j].around);
  }
  template <class F>
  static void for_cells(const std::array<Vec2, 4>& box, F&& f) {
    print_detail::cells_of(box, kCell).for_each([&](std::int64_t x, std::int64_t y) {
      f(print_detail::cell_key(x, y));
    });
  }
  std::vector<Label>& labels_;
  std::vector<Kept> kept_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

/// What of a net is paper cut out with its pieces, on a grid of cells: its faces, and its cut
/// lines (the sides of faces at cut edges and at the model's boundary).
class PaperGrid {
 public:
  PaperGrid(const std::vector<std::array<Vec2, 3>>& faces, const std::vector<NetEdge>& edges,
            const std::vector<int>& piece)
      : faces_(faces), piece_(piece) {
    for (int f = 0; f < static_cast<int>(faces.size()); ++f)
      for_cells(faces[f], [&](std::uint64_t key) { cells_[key].faces.push_back(f); });
    folds_.resize(faces.size());
    for (const NetEdge& e : edges) {
      if (e.kind != EdgeKind::Cut) {
        if (e.b.face < 0 || (!piece.empty() && piece[e.a.face] != piece[e.b.face])) continue;
        const auto& t = faces[e.a.face];
        const Fold fold{e.b.face, t[e.a.k], t[(e.a.k + 1) % 3]};
        folds_[e.a.face].push_back(fold);
        folds_[e.b.face].push_back({e.a.face, fold.b, fold.a});
        continue;
      }
      for (const EdgeSide side : {e.a, e.b}) {
        if (side.face < 0) continue;
        const auto& t = faces[side.face];
        const std::array<Vec2, 2> cut{t[side.k], t[(side.k + 1) % 3]};
        const auto index = static_cast<int>(cuts_.size());
        cuts_.push_back(cut);
        for_cells(cut, [&](std::uint64_t key) { cells_[key].cuts.push_back(index); });
      }
    }
  }
  /// True when `p` lies on a face of the piece of face `face` (on any face without pieces).
  bool on_piece(Vec2 p, int face) const {
    const auto it = cells_.find(key_of(p));
    if (it == cells_.end()) return false;
    for (const int f : it->second.faces) {
      if (!piece_.empty() && piece_[f] != piece_[face]) continue;
      const auto& t = faces_[f];
      const double c0 = cross(t[1] - t[0], p - t[0]), c1 = cross(t[2] - t[1], p - t[1]);
      const double c2 = cross(t[0] - t[2], p - t[2]);
      constexpr double kSlack = 1e-9;  // mm^2: a point on a side between two faces is on both
      if ((c0 >= -kSlack && c1 >= -kSlack && c2 >= -kSlack) ||
          (c0 <= kSlack && c1 <= kSlack && c2 <= kSlack))
        return true;
    }
    return false;
  }
  /// A fold of a face: the face across, and the side they share.
  struct Fold {
    int face;
    Vec2 a, b;
  };
  /// The folds of face `face` to faces of its piece.
  const std::vector<Fold>& folds(int face) const { return folds_[face]; }
  /// True when the convex polygon (or segment) `poly` meets a cut line, touching included.
  bool meets_cut(std::span<const Vec2> poly) const {
    bool hit = false;
    for_cells(poly, [&](std::uint64_t key) {
      const auto it = cells_.find(key);
      if (hit || it == cells_.end()) return;
      for (const int c : it->second.cuts)
        if (convex_overlap(cuts_[c], poly, -1e-9)) {
          hit = true;
          return;
        }
    });
    return hit;
  }

 private:
  static constexpr double kCell = 4;  // mm
  struct Cell {
    std::vector<int> faces, cuts;
  };
  static std::uint64_t key_of(Vec2 p) {
    return print_detail::cell_key(print_detail::cell_of(p.x, kCell),
                                  print_detail::cell_of(p.y, kCell));
  }
  template <class F>
  static void for_cells(std::span<const Vec2> poly, F&& f) {
    print_detail::cells_of(poly, kCell).for_each([&](std::int64_t x, std::int64_t y) {
      f(print_detail::cell_key(x, y));
    });
  }
  const std::vector<std::array<Vec2, 3>>& faces_;
  const std::vector<int>& piece_;
  std::vector<std::vector<Fold>> folds_;
  std::vector<std::array<Vec2, 2>> cuts_;
  std::unordered_map<std::uint64_t, Cell> cells_;
};

/// True when a label's text lies on faces of the piece of face `face` (a label hanging past its
/// piece's outline is cut away, one over a slit is cut in two): the centre of its box does, and
/// no cut line meets the glyphs' box, which is label_box less an eighth of its height at top and
/// bottom (digits are about 0.73 of the font size tall).
bool box_on_piece(const PaperGrid& grid, const std::array<Vec2, 4>& box, int face) {
  const Vec2 centre = 0.25 * (box[0] + box[1] + box[2] + box[3]);
  if (!grid.on_piece(centre, face)) return false;
  const Vec2 inset = 0.125 * (box[3] - box[0]);
  const std::array<Vec2, 4> glyphs{box[0] + inset, box[1] + inset, box[2] - inset, box[3] - inset};
  return !grid.meets_cut(glyphs);
}

/// The labels' indices, smallest first (then in order): the labels with the least room in their
/// face look for a place elsewhere before those with more.
std::vector<int> smallest_first(const std::vector<Label>& labels) {
  std::vector<int> order(labels.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return labels[a].size < labels[b].size; });
  return order;
}

/// Places for a label on its edge's glue tab, at kLegibleLabelMm or more, best first: as large
/// as the tab holds (at most `max_size`), its box a tenth of its height clear of the tab's fold
/// and of its top, inside the tab's ends with 5 % to spare at the box's top and bottom and with
/// 0.6 of its height to spare at either end of the text's middle line (the text does not touch
/// a cut line); the middle of the tab first, then slid towards either end; then the same at
/// kLegibleLabelMm. Low on the tab, where a tall tab over a short edge is widest, a label finds
/// room that the tab's narrow top would not give it. None when the tab is too small.
std::vector<Label> labels_on_tab(const Tab& tab, const Label& label, double max_size) {
  std::vector<Label> out;
  const auto& c = tab.corners;  // c[0], c[1] along the edge; c[2] above c[1], c[3] above c[0]
  const double base = norm(c[1] - c[0]);
  if (!(base > 0)) return out;
  const Vec2 d = (1 / base) * (c[1] - c[0]), up{-d.y, d.x};
  const double height = dot(c[2] - c[1], up);
  if (!(height > 0)) return out;
  // The tab's ends in the edge's frame: at height y they are at left(y) and right(y), and the
  // tab is narrower by `narrowing` per mm of height (positive for ends that lean in).
  const double u3 = dot(c[3] - c[0], d), u2 = dot(c[2] - c[0], d);
  const auto left = [&](double y) { return u3 * y / height; };
  const auto right = [&](double y) { return base + (u2 - base) * y / height; };
  const double narrowing = (u3 + base - u2) / height;
  const double text = 0.6 * label_chars(label.text);  // the text's width per mm of its height
  constexpr double kGap = 0.1;                        // of the text's height
  // Heights (per mm of text height) and the width wanted there.
  const std::array<std::pair<double, double>, 3> rows{
      {{kGap, 1.05 * text}, {1 + kGap, 1.05 * text}, {0.5 + kGap, text + 1.2}}};
  double fits = height / (1 + 2 * kGap);
  for (const auto& [y, width] : rows)
    if (const double wanted = width + narrowing * y; wanted > 0)  // ends leaning out: no bound
      fits = std::min(fits, base / wanted);
  for (const double size : {std::min(max_size, fits), kLegibleLabelMm}) {
    if (size < kLegibleLabelMm || size > fits) continue;
    // Where the text's middle can go: inside the ends, with room to spare, at every row.
    double lowest = -INFINITY, highest = INFINITY;
    for (const auto& [y, width] : rows) {
      lowest = std::max(lowest, left(y * size) + 0.5 * width * size);
      highest = std::min(highest, right(y * size) - 0.5 * width * size);
    }
    if (!(lowest <= highest)) continue;
    const double middle = 0.5 * (lowest + highest), slack = 0.5 * (highest - lowest);
    for (const double slide : {0.0, -0.5, 0.5, -1.0, 1.0}) {
      Label on_tab = label;
      on_tab.at = c[0] + (middle + slide * slack) * d + ((0.5 + kGap) * size) * up;
      on_tab.angle = std::atan2(d.y, d.x);
      on_tab.size = size;
      turn_upright(on_tab);
      out.push_back(on_tab);
      if (slack <= 0) break;
    }
    if (size == kLegibleLabelMm) break;
  }
  return out;
}

/// The places for a label beside its edge at kLegibleLabelMm, on its face's side, best first:
/// along the edge, the middle first, then towards its ends, then over them by the label's height
/// (the labels of a short edge at a crowded vertex find room there), then every twentieth of the
/// edge from a quarter to three quarters of it (a short edge whose face narrows to a corner off
/// its middle has room only there); its centre 0.7 of its height from the edge, else 1.7 or 2.7
/// of it (at most 4 mm: still read as the edge's). None for an edge of no length.
std::vector<Label> beside_places(const std::vector<std::array<Vec2, 3>>& faces,
                                 const Label& label) {
  std::vector<Label> out;
  const auto& tri = faces[label.side.face];
  const Vec2 p0 = tri[label.side.k], p1 = tri[(label.side.k + 1) % 3];
  const Vec2 p2 = tri[(label.side.k + 2) % 3];
  const double len = norm(p1 - p0);
  if (!(len > 0)) return out;
  const Vec2 d = (1 / len) * (p1 - p0);
  Vec2 up{-d.y, d.x};
  if (dot(p2 - p0, up) < 0) up = Vec2{0, 0} - up;
  Label beside = label;
  beside.size = kLegibleLabelMm;
  beside.angle = std::atan2(d.y, d.x);
  turn_upright(beside);
  for (const double in : {0.7, 1.7, 2.7})
    // Each place: a fraction of the edge's length, and millimetres past that.
    for (const auto& [part, past] : {std::pair{0.5, 0.0},
                                     {0.3, 0.0},
                                     {0.7, 0.0},
                                     {0.15, 0.0},
                                     {0.85, 0.0},
                                     {0.0, 0.0},
                                     {1.0, 0.0},
                                     {0.0, -kLegibleLabelMm},
                                     {1.0, kLegibleLabelMm},
                                     {0.4, 0.0},
                                     {0.6, 0.0},
                                     {0.35, 0.0},
                                     {0.65, 0.0},
                                     {0.25, 0.0},
                                     {0.75, 0.0},
                                     {0.45, 0.0},
                                     {0.55, 0.0}}) {
      beside.at = p0 + (part * len + past) * d + (in * kLegibleLabelMm) * up;
      out.push_back(beside);
    }
  return out;
}

/// True when no cut line lies between a label moved beside its edge and the edge: the line from
/// its centre to the edge's nearest point (stopped 0.05 mm short of the edge) meets none. A label
/// past a cut (the far side of a notch, reached past the edge's end) would be cut away from its
/// edge.
bool faces_its_edge(const std::vector<std::array<Vec2, 3>>& faces, const PaperGrid& grid,
                    const Label& label) {
  const auto& tri = faces[label.side.face];
  const Vec2 p0 = tri[label.side.k], p1 = tri[(label.side.k + 1) % 3];
  const Vec2 e = p1 - p0;
  const double t = std::clamp(dot(label.at - p0, e) / dot(e, e), 0.0, 1.0);
  const Vec2 on_edge = p0 + t * e;
  const double reach = norm(label.at - on_edge);
  if (reach <= 0.05) return true;
  const std::array<Vec2, 2> line{label.at, on_edge + (0.05 / reach) * (label.at - on_edge)};
  return !grid.meets_cut(line);
}

/// True when a label placed beside its edge (beside_places), whose box is `box`, lies on its
/// piece with no cut line between it and its edge.
bool beside_on_piece(const std::vector<std::array<Vec2, 3>>& faces, const PaperGrid& grid,
                     const Label& beside, const std::array<Vec2, 4>& box) {
  return box_on_piece(grid, box, beside.side.face) && faces_its_edge(faces, grid, beside);
}

/// When the labels' placement runs out of time (PrintOptions::label_seconds): never, without a
/// limit. The steps that move labels stop at it; each label they did not reach keeps the size and
/// place that fit its face.
class LabelClock {
 public:
  explicit LabelClock(double seconds)
      : limited_(std::isfinite(seconds) && seconds > 0),
        end_(std::chrono::steady_clock::now() +
             std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                 std::chrono::duration<double>(limited_ ? seconds : 0))) {}
  bool out() const { return limited_ && std::chrono::steady_clock::now() >= end_; }

 private:
  bool limited_;
  std::chrono::steady_clock::time_point end_;
};

/// Labels that did not fit their face at kLegibleLabelMm move where they print that large: onto
/// the glue tab of their side when it has room (the tab is glued away, its face's partner label
/// stays in view), else beside their edge at that size, on the face's side of it, reaching over
/// folds into the faces around, where that is on the piece (box_on_piece: `grid`) and clear of
/// every other label, of any face
/// (docs/print.md, "Labels"). Only the labels of the faces `only` marks move, when given.
/// `fitted`: each label as size_labels placed it in its face (apart from the others there),
/// where a moved label goes back when it meets another. Labels stop moving when `clock` runs out.
void make_labels_legible(const std::vector<std::array<Vec2, 3>>& faces, const PaperGrid& grid,
                         const std::vector<Tab>& tabs, const std::vector<int>& tab_of,
                         std::vector<Label>& labels, const std::vector<Label>& fitted,
                         double max_size, const LabelClock& clock,
                         const std::vector<char>* only = nullptr) {
  LabelBoxes boxes(labels);
  for (const int i : smallest_first(labels)) {
    if (clock.out()) break;
    const Label& label = labels[i];
    if (label.text.empty() || label.size >= kLegibleLabelMm) continue;
    if (only && !(*only)[label.side.face]) continue;
    const int t = tab_of[label.edge];
    if (t >= 0 && tabs[t].side.face == label.side.face && tabs[t].side.k == label.side.k) {
      bool moved = false;
      for (const Label& on_tab : labels_on_tab(tabs[t], label, max_size))
        if (!boxes.collides(on_tab, i)) {
          boxes.move(i, on_tab);
          moved = true;
          break;
        }
      if (moved) continue;
    }
    for (const Label& beside : beside_places(faces, label))
      // Clear of the other labels (the cheaper test), and on the piece.
      if (!boxes.collides(beside, i) && beside_on_piece(faces, grid, beside, label_box(beside))) {
        boxes.move(i, beside);
        break;
      }
  }
  // A label put back at its fitted size may meet one moved before it: that one goes back too,
  // until none meet (the fitted labels are apart, so this ends).
  for (bool changed = true; changed;) {
    changed = false;
    for (int i = 0; i < static_cast<int>(labels.size()); ++i)
      if (labels[i].size != fitted[i].size && boxes.collides(labels[i], i)) {
        boxes.move(i, fitted[i]);
        changed = true;
      }
  }
}

// How near a label under the legible size a face's labels give up naming the piece across, mm.
constexpr double kCrowdedMm = 6;

/// The faces with a corner within kCrowdedMm of a label under the legible size, which found no
/// clear place: labels crowd there, at a small feature with many cut edges.
std::vector<char> faces_near_small_labels(const std::vector<std::array<Vec2, 3>>& faces,
                                          const std::vector<Label>& labels) {
  std::vector<char> near(faces.size(), 0);
  const auto cell = [](Vec2 p) {
    return print_detail::cell_key(print_detail::cell_of(p.x, kCrowdedMm),
                                  print_detail::cell_of(p.y, kCrowdedMm));
  };
  std::unordered_map<std::uint64_t, std::vector<Vec2>> small;
  for (const Label& l : labels)
    if (!l.text.empty() && l.size < kLegibleLabelMm) small[cell(l.at)].push_back(l.at);
  if (small.empty()) return near;
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (const Vec2 p : faces[f])
      for (int dy = -1; dy <= 1 && !near[f]; ++dy)
        for (int dx = -1; dx <= 1 && !near[f]; ++dx) {
          const auto it = small.find(cell(p + Vec2{dx * kCrowdedMm, dy * kCrowdedMm}));
          if (it == small.end()) continue;
          for (const Vec2 q : it->second)
            if (norm(p - q) <= kCrowdedMm) near[f] = 1;
        }
  return near;
}

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

/// Labels left under kLegibleLabelMm by every place at their edge (a short cut edge at a small
/// feature crowded with labels) print at that size, smallest first (docs/print.md, "Labels"):
/// beside their edge where a single legible label is in the way and moves (make_way), else
/// farther away, on their piece's faces, clear of every label and of the leaders drawn before,
/// with a leader line to their edge that runs over the piece and meets no other label and no
/// other leader. Places are tried on rings around the edge's middle, 2 to 15 mm, nearest first,
/// from the face's side round to the other, the text along the edge, level, or across the edge
/// (along a narrow strip that ends at the edge); where no place has a straight leader, the rings
/// are tried again with a leader of two lines, bent in front of the edge; where none has that
/// either, the leader is routed over the piece's faces (route_over_piece). A label that finds
/// no place keeps its size. None moves when more than kMostFarLabels are under the legible size,
/// and none more when `clock` runs out.
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

/// "6" and "9" (and "16" and "91", ...) read as each other upside down: mark those with a dot.
std::string label_text(int number) {
  std::string text = std::to_string(number), turned;
  for (auto it = text.rbegin(); it != text.rend(); ++it) {
    const char c = *it;
    if (c != '0' && c != '1' && c != '6' && c != '8' && c != '9') return text;
    turned += c == '6' ? '9' : c == '9' ? '6' : c;
  }
  return turned == text ? text : text + ".";
}

/// Places the labels of a laid-out net (`out`, before it is moved to the origin): their sizes and
/// places, the leaders of those placed away from their edges, and each piece's number
/// (docs/print.md, "Labels"). `tab_of`: each edge's tab in `out.tabs`, or -1.
void place_labels(PrintLayout& out, const std::vector<int>& tab_of, const std::vector<int>& piece,
                  int pieces, const PrintOptions& options) {
  const PaperGrid on_paper(out.faces, out.edges, piece);
  const LabelClock clock(options.label_seconds);
  // The labels are placed in rounds: a label that names the piece across and is left under the
  // legible size by every step below (the places it found at first were taken by labels that
  // moved after) gives up the name from the start of the next round, in which its face's labels
  // are placed again around the shorter text (docs/print.md, "Build order"). A round is kept when
  // it leaves fewer labels under the legible size than the one before; at most three rounds.
  const std::vector<Label> named = out.labels;
  std::vector<char> plain(named.size(), 0);
  std::vector<Label> kept_labels;
  std::vector<Segment> kept_leaders;
  std::size_t kept_small = 0;
  for (int round = 0;; ++round) {
    out.labels = named;
    for (std::size_t i = 0; i < named.size(); ++i)
      if (plain[i]) out.labels[i].text = label_text(out.edges[named[i].edge].cut_index + 1);
    out.leaders.clear();
    size_labels(out.faces, out.labels, options.max_label_mm);
    std::vector<Label> fitted = out.labels;
    make_labels_legible(out.faces, on_paper, out.tabs, tab_of, out.labels, fitted,
                        options.max_label_mm, clock);
    // A label naming the piece across ("12→P3") that prints under the legible size even so, and
    // even away from its edge with a leader line (a sliver with two cut edges), becomes the plain
    // number, and its face's labels are placed again: its twin still names the piece
    // (docs/print.md, "Build order").
    std::vector<Label> trial = out.labels;
    if (options.labels) place_far_labels(out.faces, on_paper, trial, clock);
    std::vector<char> again(out.faces.size(), 0);
    bool shorten = false;
    for (const Label& l : trial) {
      if (l.size >= kLegibleLabelMm || l.text == label_text(out.edges[l.edge].cut_index + 1))
        continue;
      again[l.side.face] = 1;
      shorten = true;
    }
    if (shorten) {
      std::vector<int> index;
      std::vector<Label> redo;
      for (int i = 0; i < static_cast<int>(out.labels.size()); ++i) {
        if (!again[out.labels[i].side.face]) continue;
        Label l = out.labels[i];
        if (trial[i].size < kLegibleLabelMm) l.text = label_text(out.edges[l.edge].cut_index + 1);
        index.push_back(i);
        redo.push_back(std::move(l));
      }
      size_labels(out.faces, redo, options.max_label_mm);
      for (std::size_t j = 0; j < index.size(); ++j)
        fitted[index[j]] = out.labels[index[j]] = redo[j];
      make_labels_legible(out.faces, on_paper, out.tabs, tab_of, out.labels, fitted,
                          options.max_label_mm, clock, &again);
    }
    // Where a label would still print under the legible size even away from its edge with a
    // leader line (a small feature with many short cut edges), the labels moved beside their edges
    // around it give up naming the piece across, in place (their boxes shrink about their
    // centres), and the small labels look for room again. Of the two labels of an edge one keeps
    // the name: the one whose twin prints under the legible size or plain already, else the one on
    // the edge's second side when both are crowded (docs/print.md, "Build order").
    trial = out.labels;
    std::vector<Segment> trial_leaders;
    if (options.labels) trial_leaders = place_far_labels(out.faces, on_paper, trial, clock);
    bool gave = false;
    if (const std::vector<char> crowded = faces_near_small_labels(out.faces, trial);
        std::find(crowded.begin(), crowded.end(), 1) != crowded.end()) {
      std::vector<int> twin(out.labels.size(), -1), first(out.edges.size(), -1);
      for (int i = 0; i < static_cast<int>(out.labels.size()); ++i) {
        int& f = first[out.labels[i].edge];
        if (f < 0) {
          f = i;
        } else {
          twin[i] = f;
          twin[f] = i;
        }
      }
      const auto gives_way = [&](int i) {
        const Label& l = out.labels[i];
        const bool moved =
            l.size != fitted[i].size || l.at.x != fitted[i].at.x || l.at.y != fitted[i].at.y;
        if (!crowded[l.side.face] || !moved || l.size < kLegibleLabelMm) return false;
        if (twin[i] < 0) return true;
        const Label& other = out.labels[twin[i]];
        if (other.size < kLegibleLabelMm ||
            other.text == label_text(out.edges[l.edge].cut_index + 1))
          return false;  // the twin prints small, or gave the name up before
        return !crowded[other.side.face] || l.side.face == out.edges[l.edge].a.face;
      };
      for (int i = 0; i < static_cast<int>(out.labels.size()); ++i) {
        const std::string plain = label_text(out.edges[out.labels[i].edge].cut_index + 1);
        if (out.labels[i].text == plain || !gives_way(i)) continue;
        out.labels[i].text = fitted[i].text = plain;
        gave = true;
      }
      if (gave)
        make_labels_legible(out.faces, on_paper, out.tabs, tab_of, out.labels, fitted,
                            options.max_label_mm, clock);
    }
    // The last trial is the result unless labels gave up their names since.
    if (!gave) {
      out.labels = std::move(trial);
      out.leaders = std::move(trial_leaders);
    } else if (options.labels) {
      out.leaders = place_far_labels(out.faces, on_paper, out.labels, clock);
    }
    const auto small = static_cast<std::size_t>(
        std::count_if(out.labels.begin(), out.labels.end(),
                      [](const Label& l) { return !l.text.empty() && l.size < kLegibleLabelMm; }));
    if (round > 0 && small >= kept_small) {
      out.labels = std::move(kept_labels);
      out.leaders = std::move(kept_leaders);
      break;
    }
    bool more = false;
    for (std::size_t i = 0; round < 2 && i < out.labels.size(); ++i) {
      const Label& l = out.labels[i];
      if (l.text.empty() || l.size >= kLegibleLabelMm ||
          l.text == label_text(out.edges[l.edge].cut_index + 1))
        continue;
      plain[i] = 1;
      more = true;
    }
    // Another round only while the clock lasts: this one's labels are kept as they are.
    if (!more || clock.out()) break;
    kept_labels = out.labels;
    kept_leaders = out.leaders;
    kept_small = small;
  }
  if (pieces > 1)
    out.piece_labels = print_detail::place_piece_labels(out.faces, out.labels, out.leaders, piece);
}

}  // namespace

double print_scale(const Mesh& mesh, const PrintOptions& options) {
  if (options.scale > 0) return options.scale;
  const Vec3 size = bounding_box(mesh).size();
  const double extent = std::max({size.x, size.y, size.z});  // -inf without vertices
  return extent > 0 && std::isfinite(extent) ? options.size_mm / extent : 1;
}

bool makes_tab_room(const PrintOptions& options) {
  return options.tabs == TabMode::Auto && options.tab_height_mm > 0 && options.tab_room_budget > 0;
}

TabClearanceOptions tab_clearance_options(const Mesh& mesh, const PrintOptions& options) {
  TabClearanceOptions clearance;
  const double mm = std::min(options.min_tab_height_mm, options.tab_height_mm);
  clearance.min_height = mm / print_scale(mesh, options);
  clearance.angle_deg = options.tab_angle_deg;
  clearance.time_limit_seconds = options.tab_room_seconds;
  clearance.max_evaluations = options.tab_room_budget;
  return clearance;
}

PrintLayout layout_net(const Mesh& mesh, const Net& net, const PrintOptions& options,
                       const std::vector<int>& piece, const LargeFaces& large,
                       LabelPass label_pass) {
  options.validate();
  if (mesh.faces.empty()) throw InvalidInputException("nothing to print: the mesh has no faces");
  if (net.points.size() != mesh.faces.size() || net.parent.size() != mesh.faces.size())
    throw InvalidInputException("the net has " + std::to_string(net.points.size()) +
                                " faces but the mesh has " + std::to_string(mesh.faces.size()));
  const auto nv = static_cast<int>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (const int v : mesh.faces[f])
      if (v < 0 || v >= nv)
        throw InvalidInputException("mesh face " + std::to_string(f) + " refers to vertex " +
                                    std::to_string(v) + " of " + std::to_string(nv));
  for (std::size_t f = 0; f < net.points.size(); ++f)
    for (const Vec2 p : net.points[f])
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        throw InvalidInputException("net face " + std::to_string(f) + " has a non-finite point");
  if (!piece.empty() && piece.size() != mesh.faces.size())
    throw InvalidInputException("the net has " + std::to_string(piece.size()) +
                                " faces with a piece but the mesh has " +
                                std::to_string(mesh.faces.size()));
  if (!large.face.empty() && large.face.size() != mesh.faces.size())
    throw InvalidInputException("the net has " + std::to_string(large.face.size()) +
                                " faces marked large or not but the mesh has " +
                                std::to_string(mesh.faces.size()));
  int pieces = 0;
  for (const int p : piece) {
    if (p < 0) throw InvalidInputException("a face has a negative piece");
    pieces = std::max(pieces, p + 1);
  }
  PrintLayout out;
  out.metrics = net_metrics(mesh, net);
  out.scale = print_scale(mesh, options);

  // Rotate into the minimum-area box and scale to millimetres.
  out.faces.resize(net.points.size());
  for (std::size_t f = 0; f < net.points.size(); ++f)
    for (int k = 0; k < 3; ++k)
      out.faces[f][k] = out.scale * rotate(net.points[f][k], out.metrics.box.angle);

  out.edges = classify_edges(mesh, net, {options.flat_fold_degrees});
  // The label of cut edge `e` on side `s`: across pieces it names the piece its edge glues to
  // (docs/print.md).
  const auto text_of = [&](int e, EdgeSide s) {
    const NetEdge& edge = out.edges[e];
    const int other = s.face == edge.a.face ? edge.b.face : edge.a.face;
    const bool joins = !piece.empty() && other >= 0 && piece[other] != piece[s.face];
    return joins ? std::to_string(edge.cut_index + 1) + "→" + piece_name(piece[other])
                 : label_text(edge.cut_index + 1);
  };
  const TabMode mode = options.tab_height_mm > 0 ? options.tabs : TabMode::None;
  std::vector<int> bare;  // cut edges that get no tab on the net
  if (mode == TabMode::Auto) {
    TabOptions tab_options;
    tab_options.height = options.tab_height_mm;
    tab_options.angle_deg = options.tab_angle_deg;
    tab_options.min_height = options.min_tab_height_mm;
    tab_options.large = large;
    // A side whose face holds its label only under the legible size wants the edge's tab: the
    // label moves onto it (make_labels_legible), where a thin face has no room beside its edge.
    // Only where the edge is long enough for a tab over it whose top holds the label at that
    // size (45-degree ends, prefer_min_height tall): elsewhere the preference would move tabs
    // for nothing.
    if (options.labels) {
      tab_options.prefer.assign(3 * out.faces.size(), 0);
      for (int e = 0; e < static_cast<int>(out.edges.size()); ++e) {
        if (out.edges[e].cut_index < 0) continue;
        for (const EdgeSide s : {out.edges[e].a, out.edges[e].b}) {
          if (s.face < 0) continue;
          const auto& tri = out.faces[s.face];
          const std::string text = text_of(e, s);
          const double top =
              norm(tri[(s.k + 1) % 3] - tri[s.k]) - 2 * tab_options.prefer_min_height;
          if (top >= 1.15 * 0.6 * kLegibleLabelMm * label_chars(text) &&
              make_label(tri, s, text, options.max_label_mm).size < kLegibleLabelMm)
            tab_options.prefer[3 * s.face + s.k] = 1;
        }
      }
    }
    TabPlacement placed = place_tabs(out.faces, out.edges, tab_options);
    // The preference costs no glue strip: where it leaves more edges without a tab than placing
    // without it does, the tabs are placed without it.
    if (!placed.omitted.empty() && std::find(tab_options.prefer.begin(), tab_options.prefer.end(),
                                             1) != tab_options.prefer.end()) {
      tab_options.prefer.clear();
      if (TabPlacement plain = place_tabs(out.faces, out.edges, tab_options);
          plain.omitted.size() < placed.omitted.size())
        placed = std::move(plain);
    }
    out.tabs = std::move(placed.tabs);
    bare = std::move(placed.omitted);
  } else {
    for (int e = 0; e < static_cast<int>(out.edges.size()); ++e)
      if (out.edges[e].cut_index >= 0) bare.push_back(e);
  }
  if (mode == TabMode::None) {
    out.omitted_tabs = std::move(bare);
  } else {
    StripOptions strip_options;
    strip_options.max_half_width = options.tab_height_mm;
    strip_options.min_half_width =
        std::max(1.0, std::min(options.min_tab_height_mm, options.tab_height_mm));
    out.strips =
        place_strips(out.faces, out.tabs, strip_requests(out.faces, out.edges, bare, strip_options),
                     {}, strip_options);
    for (GlueStrip& s : out.strips) {
      if (!options.labels) continue;
      s.text = label_text(out.edges[s.edge].cut_index + 1);
      // As tall as fits a half of the strip, and as long as fits its length.
      const double length = norm(s.corners[1] - s.corners[0]);
      const double half = 0.5 * norm(s.corners[3] - s.corners[0]);
      const double chars = label_chars(s.text);
      s.text_size =
          std::max(kLegibleLabelMm,
                   std::min({options.max_label_mm, 0.6 * half, 0.8 * length / (0.6 * chars)}));
    }
  }

  std::vector<int> tab_of(out.edges.size(), -1);
  for (int t = 0; t < static_cast<int>(out.tabs.size()); ++t) tab_of[out.tabs[t].edge] = t;
  auto side_segment = [&](EdgeSide s) {
    return Segment{out.faces[s.face][s.k], out.faces[s.face][(s.k + 1) % 3], s.face};
  };
  for (int e = 0; e < static_cast<int>(out.edges.size()); ++e) {
    const NetEdge& edge = out.edges[e];
    const bool draw_fold = edge.kind != EdgeKind::Flat || options.draw_flat_folds;
    if (edge.kind != EdgeKind::Cut) {
      if (draw_fold) (edge.fold > 0 ? out.mountain : out.valley).push_back(side_segment(edge.a));
      continue;
    }
    if (edge.cut_index >= 0) ++out.cut_edges;
    for (EdgeSide s : {edge.a, edge.b}) {
      if (s.face < 0) continue;
      const int t = tab_of[e];
      if (t >= 0 && out.tabs[t].side.face == s.face && out.tabs[t].side.k == s.k) {
        const auto& c = out.tabs[t].corners;
        const Segment edge_line = side_segment(s);
        // A tab on part of the edge: the rest of the edge is still cut.
        if (norm(c[1] - edge_line.a) > 0) out.cut.push_back({edge_line.a, c[1], s.face});
        if (norm(edge_line.b - c[0]) > 0) out.cut.push_back({c[0], edge_line.b, s.face});
        out.mountain.push_back({c[1], c[0], s.face});
        out.cut.push_back({c[1], c[2], s.face});
        out.cut.push_back({c[2], c[3], s.face});
        out.cut.push_back({c[3], c[0], s.face});
      } else {
        out.cut.push_back(side_segment(s));
      }
      if (options.labels && edge.cut_index >= 0)
        out.labels.push_back({{}, 0, 0, text_of(e, s), e, s});
    }
  }

  if (label_pass == LabelPass::Placed) place_labels(out, tab_of, piece, pieces, options);

  // Translate so that everything starts at the origin.
  Box2 box = Box2::empty();
  for (const auto& f : out.faces)
    for (Vec2 p : f) box.add(p);
  for (const Tab& t : out.tabs)
    for (Vec2 p : t.corners) box.add(p);
  for (const GlueStrip& t : out.strips)
    for (Vec2 p : t.corners) box.add(p);
  if (out.faces.empty()) box = {};
  const Vec2 shift = Vec2{0, 0} - box.lo;
  for (auto& f : out.faces)
    for (Vec2& p : f) p = p + shift;
  for (Tab& t : out.tabs)
    for (Vec2& p : t.corners) p = p + shift;
  for (GlueStrip& t : out.strips)
    for (Vec2& p : t.corners) p = p + shift;
  for (auto* list : {&out.cut, &out.mountain, &out.valley, &out.leaders})
    for (Segment& s : *list) s = {s.a + shift, s.b + shift, s.face};
  for (Label& l : out.labels) l.at = l.at + shift;
  for (Label& l : out.piece_labels) l.at = l.at + shift;
  out.size = box.size();
  return out;
}

}  // namespace papernet
