#include "print/internal/place_labels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "print/internal/grid_cells.h"
#include "print/internal/label_leaders.h"
#include "print/internal/label_room.h"
#include "print/internal/piece_labels.h"
#include "print/labels.h"

namespace papernet {

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

namespace print_detail {
namespace {

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
  const auto cell = [](Vec2 p) { return cell_key_of(p, kCrowdedMm); };
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

}  // namespace

std::string label_text(int number) {
  std::string text = std::to_string(number), turned;
  for (auto it = text.rbegin(); it != text.rend(); ++it) {
    const char c = *it;
    if (c != '0' && c != '1' && c != '6' && c != '8' && c != '9') return text;
    turned += c == '6' ? '9' : c == '9' ? '6' : c;
  }
  return turned == text ? text : text + ".";
}

void number_cut_edges(const std::vector<std::array<Vec2, 3>>& faces, std::vector<NetEdge>& edges) {
  std::vector<int> cut;
  std::vector<double> length(edges.size(), 0);
  for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
    if (edges[e].cut_index < 0) continue;
    const EdgeSide a = edges[e].a;
    length[e] = norm(faces[a.face][(a.k + 1) % 3] - faces[a.face][a.k]);
    cut.push_back(e);
  }
  std::stable_sort(cut.begin(), cut.end(), [&](int x, int y) { return length[x] < length[y]; });
  std::vector<int> numbers(cut.size());
  std::vector<double> width(cut.size() + 1, 0);
  for (std::size_t n = 1; n <= cut.size(); ++n) {
    numbers[n - 1] = static_cast<int>(n);
    width[n] = label_chars(label_text(static_cast<int>(n)));
  }
  std::stable_sort(numbers.begin(), numbers.end(),
                   [&](int x, int y) { return width[x] < width[y]; });
  for (std::size_t i = 0; i < cut.size(); ++i) edges[cut[i]].cut_index = numbers[i] - 1;
}

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

}  // namespace print_detail
}  // namespace papernet
