#include "print/internal/label_room.h"

#include <algorithm>
#include <numbers>
#include <numeric>
#include <utility>

#include "print/internal/grid_cells.h"

namespace papernet::print_detail {
namespace {

// The side of the grids' cells, mm: about a label's length.
constexpr double kCell = 4;

/// Calls f with the key of each cell of the grid that the box around `poly` covers.
template <class F>
void for_cells(std::span<const Vec2> poly, F&& f) {
  for_each_cell_key(poly, kCell, f);
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

}  // namespace

void turn_upright(Label& label) {
  if (std::cos(label.angle) < -1e-9) label.angle += std::numbers::pi;
}

Box2 box_around(const std::array<Vec2, 4>& quad) {
  Box2 b = Box2::empty();
  for (const Vec2 p : quad) b.add(p);
  return b;
}

bool quads_meet(const std::array<Vec2, 4>& a, const Box2& a_around, const std::array<Vec2, 4>& b,
                const Box2& b_around) {
  return a_around.lo.x <= b_around.hi.x && b_around.lo.x <= a_around.hi.x &&
         a_around.lo.y <= b_around.hi.y && b_around.lo.y <= a_around.hi.y &&
         convex_overlap(a, b, 0);
}

LabelBoxes::LabelBoxes(std::vector<Label>& labels) : labels_(labels), kept_(labels.size()) {
  for (int i = 0; i < static_cast<int>(labels.size()); ++i) add(i);
}

bool LabelBoxes::collides(const Label& label, int self) const {
  return meets(label_box(label), self);
}

bool LabelBoxes::meets(const std::array<Vec2, 4>& box, int self) const {
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

std::vector<int> LabelBoxes::meeting(const std::array<Vec2, 4>& box, int self) const {
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

void LabelBoxes::move(int i, const Label& to) {
  remove(i);
  labels_[i] = to;
  add(i);
}

void LabelBoxes::remove(int i) {
  Kept& kept = kept_[i];
  if (!kept.in) return;
  kept.in = false;
  for_cells(kept.box, [&](std::uint64_t key) {
    std::vector<int>& in = cells_[key];
    in.erase(std::remove(in.begin(), in.end(), i), in.end());
  });
}

void LabelBoxes::add(int i) {
  if (labels_[i].text.empty()) return;
  remove(i);
  Kept& kept = kept_[i];
  kept = {label_box(labels_[i]), {}, true};
  kept.around = box_around(kept.box);
  for_cells(kept.box, [&](std::uint64_t key) { cells_[key].push_back(i); });
}

bool LabelBoxes::overlaps(const std::array<Vec2, 4>& box, const Box2& around, int j) const {
  if (labels_[j].text.empty()) return false;
  return quads_meet(box, around, kept_[j].box, kept_[j].around);
}

PaperGrid::PaperGrid(const std::vector<std::array<Vec2, 3>>& faces,
                     const std::vector<NetEdge>& edges, const std::vector<int>& piece)
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

bool PaperGrid::on_piece(Vec2 p, int face) const {
  const auto it = cells_.find(cell_key_of(p, kCell));
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

bool PaperGrid::meets_cut(std::span<const Vec2> poly) const {
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

bool box_on_piece(const PaperGrid& grid, const std::array<Vec2, 4>& box, int face) {
  const Vec2 centre = 0.25 * (box[0] + box[1] + box[2] + box[3]);
  if (!grid.on_piece(centre, face)) return false;
  const Vec2 inset = 0.125 * (box[3] - box[0]);
  const std::array<Vec2, 4> glyphs{box[0] + inset, box[1] + inset, box[2] - inset, box[3] - inset};
  return !grid.meets_cut(glyphs);
}

std::vector<int> smallest_first(const std::vector<Label>& labels) {
  std::vector<int> order(labels.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return labels[a].size < labels[b].size; });
  return order;
}

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

bool beside_on_piece(const std::vector<std::array<Vec2, 3>>& faces, const PaperGrid& grid,
                     const Label& beside, const std::array<Vec2, 4>& box) {
  return box_on_piece(grid, box, beside.side.face) && faces_its_edge(faces, grid, beside);
}

}  // namespace papernet::print_detail
