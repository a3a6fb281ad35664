#pragma once

#include <vector>

#include "print/build_order.h"
#include "print/layout.h"
#include "print/pages.h"

namespace papernet {

/// What the overview page of a fit layout shows (docs/print.md, "The overview page"): each
/// sheet drawn small with its pieces and their numbers, the sheet list (which pieces each page
/// holds) and the build order (which earlier pieces each piece glues to).
struct Overview {
  std::vector<int> page;   ///< each piece's page (index into PageLayout::pages), -1: none
  std::vector<int> piece;  ///< each face's piece
  PieceGraph graph;        ///< which pieces glue to which
};

/// Puts an overview page first in `pages` (a fit layout: nest_pages), so every other page moves
/// one on; `piece` gives each face of `layout` its piece (numbered in build order), `graph` the
/// pieces' neighbours (piece_graph). Each piece's page is the page that holds its first face.
void add_overview(PageLayout& pages, const PrintLayout& layout, const std::vector<int>& piece,
                  PieceGraph graph);

/// The shapes of the overview page `index` (without its page number: draw_page adds it). The
/// sheets as thumbnails (their printable area dashed, the pieces' cut lines, each piece's
/// number), each captioned "page k: P1, P4"; below, the build order ("P3 glues to P1, P2").
PageDrawing draw_overview(const PrintLayout& layout, const PageLayout& pages, int index);

}  // namespace papernet
