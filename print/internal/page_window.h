#pragma once
// Which page a point of a laid-out net lies on: the overview (print/overview.cpp, its thumbnails
// in print/overview_sheets.cpp) and the pieces' placements (print/placements.cpp) find each
// piece's page by it.

#include "core/vec.h"
#include "print/pages.h"

namespace papernet::print_detail {

/// True when `p` lies in the window of the layout that `page` prints (its sides included; an
/// overview page holds no point).
inline bool holds(const Page& page, Vec2 p) {
  return p.x >= page.lo.x && p.x <= page.hi.x && p.y >= page.lo.y && p.y <= page.hi.y;
}

}  // namespace papernet::print_detail
