// Private to engine/: the resolution of the print's colour paced against the job's deadline
// (docs/colour.md, "Time limit").
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <vector>

#include "api/net_json.h"
#include "print/pages.h"

namespace papernet::engine_detail {

/// The most pixels the colour of one drawing of the whole net may hold (its images are held at
/// once until written): an A0 sheet's printable area at 300 dpi, as many as the largest page's.
inline constexpr double kMostDrawingPixels = 140e6;

/// Paces the drawing of coloured pages against the print's deadline. A page's cost is taken to
/// be its pixels (rasterising them and cairo's zlib compression of them): its printable area at
/// the resolution drawn (an overview page's views are drawn before, at their own resolution:
/// none). Before each page is drawn the seconds per pixel are measured over the pages drawn since
/// the last change, or, before any, taken from the machine (a prior: one A0 page at 300 dpi takes
/// 4 s, which alone overran a short limit); when the pages left would take longer than the time
/// left, the resolution drops so that they fit, to at least kMinColourDpi. It never rises again:
/// the pages of a kit differ at most from sharp to less sharp, once or a few times. When the
/// pages left would take longer even at kMinColourDpi (hundreds of pages of a net tiled on small
/// paper, each painting its faces' many small triangles: a cost per triangle, not per pixel),
/// they print without colour.
class ColourPace {
 public:
  /// `seconds_per_pixel`: the prior for a page drawn and written once, used until a page with
  /// colour has been drawn; `writes`: the documents each page is written into (the PDF, the SVG
  /// pages), each compressing its images (in the SVG as PNG) about as long as the other.
  ColourPace(std::chrono::steady_clock::time_point deadline, double dpi, const PageLayout& pages,
             double seconds_per_pixel, int writes);

  /// The resolution to draw page `page` at, the pages before it drawn and all but the last of
  /// them written; 0: no colour, on this page and the rest.
  double next_dpi(int page);

  /// The seconds a pixel takes drawn and written once: as measured over the pages, else the
  /// prior.
  double seconds_per_pixel_written_once() const { return per_pixel_ * drawn_share_ / kDrawnShare; }

  /// The warnings for pages drawn at a lower resolution than asked, and for pages drawn without
  /// colour, of `pages`.
  std::vector<NetRepair> warnings(int pages) const;

 private:
  // A page's share of its cost that is its drawing (its colour rasterised) rather than its
  // writing into one document (compressed into the PDF), which runs beside the next page's
  // drawing: the Duck on A0 paper at 300 dpi, 2.5 s and 4 s (the SVG's PNG 3.7 s).
  static constexpr double kDrawnShare = 0.4;

  static double squared(double dpi) { return (dpi / 25.4) * (dpi / 25.4); }
  double pixels(std::size_t page, double dpi) const { return areas_[page] * squared(dpi); }

  std::chrono::steady_clock::time_point deadline_;
  double asked_, dpi_;
  double drawn_share_;             // of a page's cost, with its writes
  double per_pixel_;               // seconds
  std::vector<double> areas_;      // of each page that its colour may cover, mm²
  std::vector<double> drawn_dpi_;  // each page's resolution, once chosen
  double drawn_ = 0;               // pixels of the pages drawn so far
  std::chrono::steady_clock::time_point since_ = std::chrono::steady_clock::now();
  double done_since_ = 0;  // pixels done when the resolution last changed
  int measured_ = 0;       // pages measured at the resolution
  int first_lowered_ = -1;
  int first_without_ = -1;
};

/// The resolution of the colour of one drawing of the whole net, whose images hold `pixels(d)`
/// pixels at d dpi: `asked`, lowered to the highest whole dpi whose pixels `seconds` draw (and
/// write once) at `per_pixel` seconds a pixel (0: no bound) after `fixed` seconds whatever the
/// resolution, and at most kMostDrawingPixels; 0 (line art) when that is below kMinColourDpi.
/// `by_time`: whether the time lowered it below what the pixels allow.
double drawing_dpi(double asked, const std::function<double(double)>& pixels, double seconds,
                   double per_pixel, double fixed, bool& by_time);

}  // namespace papernet::engine_detail
