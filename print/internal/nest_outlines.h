#pragma once
// Outlines placed on sheets (print/nest.cpp's backend; docs/print.md, "Fit layout").

#include <cstdint>
#include <vector>

namespace papernet::print_detail {

struct IntPoint {
  std::int64_t x = 0, y = 0;
};

/// Where one outline goes: sheet `sheet` (-1: it fits no sheet), turned by `angle`
/// radians counter-clockwise about the origin, then moved by (`dx`, `dy`).
struct NestedOutline {
  int sheet = -1;
  double angle = 0;
  std::int64_t dx = 0, dy = 0;
};

/// One part to nest: its polygons (a piece's faces and tabs, or a glue strip), each closed and
/// simple, together an overlap-free cover of the part.
using NestPart = std::vector<std::vector<IntPoint>>;

/// Nests parts into few `width` x `height` sheets, each part's polygons grown by `grow` (the
/// paper kept around a part): each part, in its four quarter turns, is covered by cells of 0.5 mm
/// (500 units; every cell one of its grown polygons touches: the polygons are grown and
/// rasterised one by one, never joined, as the part comes; its cells turned give the other three
/// turns), and, largest first, goes on the first sheet where a turn of it touches no cell already
/// taken, at the lowest, then leftmost, such cell (bottom-left fill). No two parts placed on a
/// sheet share a cell, so none overlap. A part that no empty grid holds (its cells reach past the
/// sheet) gets a sheet of its own at its exact place, untouched, when its grown box fits the
/// sheet; else its sheet is -1. "Largest" is tried three ways (by area, by longest side, by box
/// area), and from the order of fewest sheets the parts of its last sheet are then moved to the
/// front while that takes fewer (at most 3 times). Returns one placement per part, in order.
std::vector<NestedOutline> nest_outlines(const std::vector<NestPart>& parts, std::int64_t grow,
                                         std::int64_t width, std::int64_t height);

}  // namespace papernet::print_detail
