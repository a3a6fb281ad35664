#pragma once

#include <string>

#include "print/layout.h"
#include "print/pages.h"

namespace papernet {

/// A PDF (cairo) with one page per entry of `pages`, drawn like the SVG pages: cut lines solid,
/// mountain folds dashed, valley folds dash-dotted, tabs shaded, glue strips, labels, overlap
/// marks; with `colour`, each coloured piece's image (an image XObject) over the faces and tabs.
/// Pages are drawn one at a time. Returns the PDF's bytes.
/// \throw IOException when cairo fails.
std::string write_pdf(const PrintLayout& layout, const PageLayout& pages,
                      const PrintColour* colour = nullptr);

}  // namespace papernet
