#pragma once
// The one place libnest2d is called (print/nest.cpp's backend). Plain C++17 on both sides: this
// file's .cpp is compiled as C++17, because libnest2d 5.0's headers do not compile as C++20
// (comparisons of its Radians become ambiguous with C++20's rewritten operators).

#include <cstdint>
#include <vector>

namespace papernet::print_detail {

struct IntPoint {
  std::int64_t x = 0, y = 0;
};

/// Where libnest2d put one outline: sheet `sheet` (-1: it fits no sheet), turned by `angle`
/// radians counter-clockwise about the origin, then moved by (`dx`, `dy`).
struct NestedOutline {
  int sheet = -1;
  double angle = 0;
  std::int64_t dx = 0, dy = 0;
};

/// Nests closed outlines (each a simple polygon, clockwise, first point repeated last) into the
/// fewest `width` x `height` sheets with the bottom-left placer, first fit (largest first),
/// quarter turns allowed. Returns one placement per outline, in order.
std::vector<NestedOutline> nest_outlines(const std::vector<std::vector<IntPoint>>& outlines,
                                         std::int64_t width, std::int64_t height);

}  // namespace papernet::print_detail
