// Checks of drawn pages against the paper, for tests that read a print back from its SVG
// (tests/support/svg.h) rather than from the layout's own data.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/vec.h"
#include "print/pages.h"
#include "tests/support/polygons.h"

namespace papernet::test {

/// Checks the shapes drawn on one page of `page`'s paper (mm): every point on the printable area
/// (the paper less its margins; SVG numbers are rounded to 1 µm), and no two shapes overlapping
/// by more than that. `where` names the page in a failure.
inline void expect_on_the_printable_area_apart(const std::vector<std::vector<Vec2>>& shapes,
                                               const PageOptions& page, const std::string& where) {
  for (const auto& shape : shapes)
    for (Vec2 p : shape) {
      EXPECT_GE(p.x, page.margin_mm - 1e-3) << where;
      EXPECT_GE(p.y, page.margin_mm - 1e-3) << where;
      EXPECT_LE(p.x, page.paper.width - page.margin_mm + 1e-3) << where;
      EXPECT_LE(p.y, page.paper.height - page.margin_mm + 1e-3) << where;
    }
  for (std::size_t i = 0; i < shapes.size(); ++i)
    for (std::size_t j = i + 1; j < shapes.size(); ++j)
      EXPECT_LE(overlap_thickness(shapes[i], shapes[j]), 1e-3)
          << where << ": shapes " << i << " and " << j << " overlap";
}

}  // namespace papernet::test
