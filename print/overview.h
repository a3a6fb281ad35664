#pragma once

#include <memory>
#include <vector>

#include "core/mesh/mesh.h"
#include "print/build_order.h"
#include "print/layout.h"
#include "print/model_view.h"
#include "print/pages.h"

namespace papernet {

/// What the overview page of a fit layout shows (docs/print.md, "The overview page"): each
/// sheet drawn small with its pieces and their numbers, the model as built with its pieces
/// numbered (from the front and from the back), the sheet list (which pieces each page holds)
/// and the build order (which earlier pieces each piece glues to).
struct OverviewPlan;  // what each overview page shows (print/overview.cpp)

struct Overview {
  std::vector<int> page;   ///< each piece's page (index into PageLayout::pages), -1: none
  std::vector<int> piece;  ///< each face's piece
  PieceGraph graph;        ///< which pieces glue to which
  Mesh model;              ///< the mesh the net folds into (no faces: no views of it)
  ViewAxes axes;
  bool colour = true;  ///< the views' pieces in colours of their own, else grey
  std::shared_ptr<const OverviewPlan> plan;
};

/// Puts the overview first in `pages` (a fit layout: nest_pages), so every other page moves on:
/// one page, or more when its sheets and build order do not fit one legibly (docs/print.md, "The
/// overview page"); `piece` gives each face of `layout` its piece (numbered in build order),
/// `graph` the pieces' neighbours (piece_graph), `model` the mesh the net folds into (its faces
/// those of `layout`; none: the overview shows no views of the model), `axes` its up and front and
/// `colour` whether the views show each piece in a colour of its own. Each piece's page is the
/// page that holds its first face. False, and `pages` as they were, where the paper is too small
/// for a legible overview (its header's words wider than the printable area, or too little
/// room below it for a row of thumbnails or for a few lines of the build order).
bool add_overview(PageLayout& pages, const PrintLayout& layout, const std::vector<int>& piece,
                  PieceGraph graph, Mesh model = {}, ViewAxes axes = {}, bool colour = true);

/// The shapes of the overview page `index` (without its page number: draw_page adds it). The
/// sheets as thumbnails (their printable area dashed, the pieces' cut lines, each piece's
/// number), each captioned "page k: P1, P4", and after them the model from the front and the
/// back (draw_model_view); below, the build order ("P3 glues to P1, P2").
PageDrawing draw_overview(const PrintLayout& layout, const PageLayout& pages, int index);

}  // namespace papernet
