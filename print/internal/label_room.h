#pragma once
// Where a label of a laid-out net has room (print/label_room.cpp): the grids of the labels' boxes
// and of the paper cut out, and the places beside an edge, shared by the labels' placement
// (print/labels.cpp) and the labels led away from their edges (print/label_leaders.cpp).

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "core/vec.h"
#include "print/layout.h"

namespace papernet::print_detail {

/// Text turned half a turn when it would read upside down (its box stays the same).
void turn_upright(Label& label);

/// The axis-aligned box around a quadrilateral (a label's box, a leader's).
Box2 box_around(const std::array<Vec2, 4>& quad);

/// True when two quadrilaterals overlap, each given with the box around it (which rules out most
/// pairs sooner).
bool quads_meet(const std::array<Vec2, 4>& a, const Box2& a_around, const std::array<Vec2, 4>& b,
                const Box2& b_around);

/// The boxes of a net's labels on a grid of cells, as the labels move: which other label a box
/// meets, on any face (a label moved beside its edge reaches over folds into other faces).
class LabelBoxes {
 public:
  explicit LabelBoxes(std::vector<Label>& labels);
  /// True when `label`'s box meets the box of a label other than label `self`.
  bool collides(const Label& label, int self) const;
  /// True when `box` meets the box of a label other than label `self`.
  bool meets(const std::array<Vec2, 4>& box, int self) const;
  /// The labels other than label `self` whose boxes `box` meets.
  std::vector<int> meeting(const std::array<Vec2, 4>& box, int self) const;
  /// Label `i` moves to `to` (a place, size or angle of its own), its box with it.
  void move(int i, const Label& to);

 private:
  // A label's box as added, and the box around it (which rules out most pairs sooner).
  struct Kept {
    std::array<Vec2, 4> box;
    Box2 around;
    bool in = false;
  };
  void remove(int i);
  void add(int i);
  bool overlaps(const std::array<Vec2, 4>& box, const Box2& around, int j) const;
  std::vector<Label>& labels_;
  std::vector<Kept> kept_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

/// What of a net is paper cut out with its pieces, on a grid of cells: its faces, and its cut
/// lines (the sides of faces at cut edges and at the model's boundary).
class PaperGrid {
 public:
  PaperGrid(const std::vector<std::array<Vec2, 3>>& faces, const std::vector<NetEdge>& edges,
            const std::vector<int>& piece);
  /// True when `p` lies on a face of the piece of face `face` (on any face without pieces).
  bool on_piece(Vec2 p, int face) const;
  /// A fold of a face: the face across, and the side they share.
  struct Fold {
    int face;
    Vec2 a, b;
  };
  /// The folds of face `face` to faces of its piece.
  const std::vector<Fold>& folds(int face) const { return folds_[face]; }
  /// True when the convex polygon (or segment) `poly` meets a cut line, touching included.
  bool meets_cut(std::span<const Vec2> poly) const;

 private:
  struct Cell {
    std::vector<int> faces, cuts;
  };
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
bool box_on_piece(const PaperGrid& grid, const std::array<Vec2, 4>& box, int face);

/// The labels' indices, smallest first (then in order): the labels with the least room in their
/// face look for a place elsewhere before those with more.
std::vector<int> smallest_first(const std::vector<Label>& labels);

/// The places for a label beside its edge at kLegibleLabelMm, on its face's side, best first:
/// along the edge, the middle first, then towards its ends, then over them by the label's height
/// (the labels of a short edge at a crowded vertex find room there), then every twentieth of the
/// edge from a quarter to three quarters of it (a short edge whose face narrows to a corner off
/// its middle has room only there); its centre 0.7 of its height from the edge, else 1.7 or 2.7
/// of it (at most 4 mm: still read as the edge's). None for an edge of no length.
std::vector<Label> beside_places(const std::vector<std::array<Vec2, 3>>& faces, const Label& label);

/// True when a label placed beside its edge (beside_places), whose box is `box`, lies on its
/// piece with no cut line between it and its edge.
bool beside_on_piece(const std::vector<std::array<Vec2, 3>>& faces, const PaperGrid& grid,
                     const Label& beside, const std::array<Vec2, 4>& box);

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

}  // namespace papernet::print_detail
