// Glue tab shapes shared by the tab clearance pass and the print layout's placer.
#include "core/tabs/tab_clearance.h"

#include <cmath>
#include <numbers>
#include <utility>

namespace papernet {

namespace {

/// Stretches of the edge a tab's base may cover, best first (as the print layout's placer).
constexpr std::array<std::pair<double, double>, 9> kSpans = {{{0, 1},
                                                              {0.1, 0.9},
                                                              {0, 0.7},
                                                              {0.3, 1},
                                                              {0.2, 0.8},
                                                              {0, 0.45},
                                                              {0.55, 1},
                                                              {0.3, 0.7},
                                                              {0.05, 0.5}}};

}  // namespace

std::vector<TabShape> tab_shapes(double angle_deg) {
  const double a = angle_deg * std::numbers::pi / 180;
  std::vector<TabShape> out;
  for (const auto& [from, to] : kSpans)
    for (double s0 : {a, 0.4 * a})
      for (double s1 : {a, 0.4 * a}) out.push_back({from, to, std::tan(s0), std::tan(s1)});
  return out;
}

std::array<Vec2, 4> tab_trapezoid(const std::array<Vec2, 3>& face, int k, const TabShape& shape,
                                  double height) {
  const Vec2 e0 = face[k], e1 = face[(k + 1) % 3];
  const double full = norm(e1 - e0);
  const Vec2 d = (1 / full) * (e1 - e0), out{d.y, -d.x};  // the face is on the left of e0->e1
  const Vec2 p0 = e0 + shape.from * full * d, p1 = e0 + shape.to * full * d;
  const double len = (shape.to - shape.from) * full;
  double i0 = height / shape.tan0, i1 = height / shape.tan1;
  if (i0 + i1 > 0.9 * len) {
    const double s = 0.9 * len / (i0 + i1);
    i0 *= s, i1 *= s;
  }
  return {p1, p0, p0 + height * out + i0 * d, p1 + height * out - i1 * d};
}

}  // namespace papernet
