#pragma once

#include <memory>
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

/// A PDF written a page at a time, each page drawn as write_pdf draws it: a caller that also
/// writes each page's SVG draws (and colours) every page once, and can stop between pages.
class PdfWriter {
 public:
  /// Pages of `width_mm` x `height_mm`; the document's metadata counts `layout`'s parts.
  /// \throw IOException when cairo cannot create the document.
  /// With a `title` (the kit's name), the document's title is it; else "papernet paper net".
  PdfWriter(const PrintLayout& layout, double width_mm, double height_mm,
            const std::string& title = {});
  ~PdfWriter();
  PdfWriter(const PdfWriter&) = delete;
  PdfWriter& operator=(const PdfWriter&) = delete;

  void add_page(const PageDrawing& page);
  /// The PDF's bytes; no page can be added afterwards.
  /// \throw IOException when cairo failed.
  std::string finish();

 private:
  struct Cairo;
  std::string bytes_;  // where cairo's stream writes
  std::unique_ptr<Cairo> cairo_;
};

}  // namespace papernet
