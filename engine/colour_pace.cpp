// The colour's resolution paced against the job's deadline (engine/internal/colour_pace.h).
#include "engine/internal/colour_pace.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "print/colour.h"

namespace papernet::engine_detail {
namespace {

// Pages measured at the lowest resolution before their pace may leave the colour out, and the
// seconds past the deadline their colour may take.
constexpr int kPagesMeasured = 2;
constexpr double kColourOverrun = 1;
constexpr double kLineArtShare = 0.05;  // of a page's time in colour, without it

}  // namespace

ColourPace::ColourPace(std::chrono::steady_clock::time_point deadline, double dpi,
                       const PageLayout& pages, double seconds_per_pixel, int writes)
    : deadline_(deadline),
      asked_(dpi),
      dpi_(dpi),
      drawn_share_(kDrawnShare / (kDrawnShare + writes * (1 - kDrawnShare))),
      per_pixel_(seconds_per_pixel * (kDrawnShare + writes * (1 - kDrawnShare))) {
  const double m = pages.margin;
  const double area = std::max(0.0, pages.width - 2 * m) * std::max(0.0, pages.height - 2 * m);
  for (const Page& page : pages.pages) areas_.push_back(page.overview ? 0 : area);
  drawn_dpi_.assign(areas_.size(), 0);
}

double ColourPace::next_dpi(int page) {
  const auto now = std::chrono::steady_clock::now();
  const auto at = static_cast<std::size_t>(page);
  // Pixels done by now: the pages before the last drawn whole, the last drawn a share (its
  // drawing, without the writing that runs beside the next page's drawing).
  const double last = at > 0 ? pixels(at - 1, drawn_dpi_[at - 1]) : 0;
  const double done = drawn_ + drawn_share_ * last;
  drawn_ += last;
  const double pending = (1 - drawn_share_) * last;
  // Measured since the last change, unless an overview page was drawn or written meanwhile
  // (its cost is not its pixels): then from now.
  const auto overview = [&](std::size_t k) { return k < at && areas_[at - 1 - k] == 0; };
  if (overview(0) || overview(1)) {
    since_ = now;
    done_since_ = done;
  } else if (dpi_ > 0 && done > done_since_) {
    per_pixel_ = std::chrono::duration<double>(now - since_).count() / (done - done_since_);
    ++measured_;
  }
  // An overview page (its views drawn already): the choice waits for the first sheet.
  if (areas_[at] == 0) return drawn_dpi_[at] = dpi_;
  double rest = 0;  // the area of the pages left, mm²
  for (std::size_t k = at; k < areas_.size(); ++k) rest += areas_[k];
  const double time_left = std::chrono::duration<double>(deadline_ - now).count();
  const auto needed = [&](double dpi) { return per_pixel_ * (pending + rest * squared(dpi)); };
  if (dpi_ == 0 || rest == 0 || needed(dpi_) <= time_left) return drawn_dpi_[at] = dpi_;
  if (dpi_ > kMinColourDpi) {
    const double room = std::max(time_left / per_pixel_ - pending, 0.0) / rest;
    const double dpi = std::max(kMinColourDpi, std::floor(25.4 * std::sqrt(room)));
    if (dpi < dpi_) {
      if (first_lowered_ < 0) first_lowered_ = page;
      dpi_ = dpi;
      since_ = now;
      done_since_ = done;
      measured_ = 0;
    }
    return drawn_dpi_[at] = dpi_;
  }
  // At the lowest resolution already, measured there: the rest in line art when they would end
  // more than the second a job may overrun its limit past it (a job late already, its few pages
  // in colour, keeps them: the Duck given 0.3 s), from the page where the time left no longer
  // holds the rest in line art (about a twentieth of a page in colour each: the milk truck's 777
  // pages tiled on 50 mm paper took 2.4 s in all without colour, 41.1 s at 50 dpi).
  const double at_least = needed(dpi_);
  if (measured_ < kPagesMeasured || at_least - std::max(time_left, 0.0) <= kColourOverrun ||
      time_left > kLineArtShare * at_least)
    return drawn_dpi_[at] = dpi_;
  first_without_ = page;
  return drawn_dpi_[at] = dpi_ = 0;
}

std::vector<NetRepair> ColourPace::warnings(int pages) const {
  std::vector<NetRepair> out;
  const auto dpi = [](double d) { return std::to_string(static_cast<long>(d)) + " dpi"; };
  const int lowered_end = first_without_ >= 0 ? first_without_ : pages;
  if (first_lowered_ >= 0 && first_lowered_ < lowered_end)
    out.push_back(
        {"colour_resolution_lowered", static_cast<std::size_t>(lowered_end - first_lowered_),
         "pages " + std::to_string(first_lowered_ + 1) + " to " + std::to_string(lowered_end) +
             " print their colour at a lower resolution than " + dpi(asked_) + " (down to " +
             dpi(first_without_ >= 0 ? kMinColourDpi : dpi_) +
             "), so that the job ends within its time limit; a longer time limit "
             "prints every page at " +
             dpi(asked_)});
  if (first_without_ >= 0)
    out.push_back({"colour_left_out", static_cast<std::size_t>(pages - first_without_),
                   "pages " + std::to_string(first_without_ + 1) + " to " + std::to_string(pages) +
                       " print without their colour (line art only): even at " +
                       dpi(kMinColourDpi) +
                       " they would not have been drawn within the job's time limit; a longer "
                       "time limit prints them in colour"});
  return out;
}

double drawing_dpi(double asked, const std::function<double(double)>& pixels, double seconds,
                   double per_pixel, double fixed, bool& by_time) {
  // The highest dpi from kMinColourDpi to `asked` whose pixels are at most `most` (0: none).
  const auto highest = [&](double most) {
    if (pixels(asked) <= most) return asked;
    if (pixels(kMinColourDpi) > most) return 0.0;
    double lo = kMinColourDpi, hi = asked;  // pixels(lo) <= most < pixels(hi)
    while (hi - lo > 1) {
      const double mid = std::floor(0.5 * (lo + hi));
      (pixels(mid) <= most ? lo : hi) = mid;
    }
    return lo;
  };
  by_time = false;
  const double by_pixels = highest(kMostDrawingPixels);
  if (by_pixels == 0 || !(per_pixel > 0) || !std::isfinite(seconds)) return by_pixels;
  const double in_time = highest(std::max(seconds - fixed, 0.0) / per_pixel);
  by_time = in_time < by_pixels;
  return in_time;
}

}  // namespace papernet::engine_detail
