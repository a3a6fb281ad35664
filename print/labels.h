#pragma once

#include <array>
#include <string>

#include "core/unfold/folds.h"
#include "core/vec.h"

// The edge labels and piece numbers a layout prints, and the room their text takes
// (print/labels.cpp; docs/print.md, "Labels").

namespace papernet {

/// A number printed inside a face next to one side of a cut edge; its twin carries the same
/// text. The text's baseline runs parallel to the edge, turned to read upright on the page
/// where it can; numbers that read as another number upside down (6, 9, 16, ...) end in a dot.
struct Label {
  Vec2 at;           ///< centre of the text box
  double angle = 0;  ///< direction of the baseline, radians counter-clockwise from +x
  double size = 0;   ///< text height (font size) in mm
  std::string text;
  int edge = -1;
  EdgeSide side;
};

/// The width of a label's text in average digit widths: 1 for each ASCII character, 1.4 for any
/// other (UTF-8) character, such as the arrow of "12→P3".
double label_chars(const std::string& text);

/// The estimated printed width of `text` at height `size` (mm): 0.6 of the size a digit, as
/// label_box.
double text_width(const std::string& text, double size);

/// Corners (counter-clockwise) of the box a label's text occupies, for an average digit width
/// of 0.6 of the font size.
std::array<Vec2, 4> label_box(const Label& label);

/// Corners (counter-clockwise) of the thin box a leader line from `a` to `b` covers: 0.2 mm
/// wide, its ends 0.05 mm short of `a` and `b` (so that it does not meet the edge it points at).
std::array<Vec2, 4> leader_box(Vec2 a, Vec2 b);

/// The smallest text a person reads on a printed kit without a magnifier, mm (a label's text
/// height; docs/print.md, "Detail").
constexpr double kLegibleLabelMm = 1.5;

/// The least gap between the labels of one face, and between a piece's number and the labels
/// around it, in text heights (the smaller label's; the piece number's own): text that touches
/// reads as one ("4→P260→P2"; docs/print.md, "Labels").
constexpr double kLabelGap = 0.15;

/// The text of a piece's number: "P" and the piece (0-based) plus one.
std::string piece_name(int piece);

}  // namespace papernet
