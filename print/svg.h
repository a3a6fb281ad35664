#pragma once

#include <string>
#include <vector>

#include "print/layout.h"
#include "print/pages.h"

namespace papernet {

/// `s` with &, <, > and " replaced by their XML entities, for text and attribute values.
std::string xml_escape(const std::string& s);

/// One SVG document for a drawing: width/height in mm, a viewBox in mm, and one <g> per layer
/// with ids faces, tabs, (colour: the drawing's images,) strips, cut, mountain, valley, leaders,
/// labels, marks (strips: glue strips' outlines solid, their seams dotted, their labels). Cut
/// lines are solid, mountain folds dashed, valley folds dash-dotted, leader lines thin solid.
/// `metadata` (e.g. omitted tab counts) goes into a <metadata> element as data-* attributes of a
/// <papernet> element.
std::string write_svg(const PageDrawing& drawing,
                      const std::vector<std::pair<std::string, std::string>>& metadata = {});

/// Metadata every print output carries: faces, cut edges, tabs, strips, omitted tabs, scale,
/// pages.
std::vector<std::pair<std::string, std::string>> layout_metadata(const PrintLayout& layout,
                                                                 int pages);

/// The net as one SVG sized to itself (no paper), with a margin; with `colour`, each coloured
/// piece's image (PNG) in a group `colour` over the faces and tabs; with a `title` (the kit's
/// name), that is its <title>.
std::string write_net_svg(const PrintLayout& layout, double margin_mm = 5,
                          const PrintColour* colour = nullptr, const std::string& title = {});

/// One SVG per page of a paginated layout (colour as write_net_svg).
std::vector<std::string> write_page_svgs(const PrintLayout& layout, const PageLayout& pages,
                                         const PrintColour* colour = nullptr);

/// The SVG of page `index` (from 0) of `pages`, drawn already (draw_page).
std::string write_page_svg(const PrintLayout& layout, const PageDrawing& page, int index,
                           int pages);

}  // namespace papernet
