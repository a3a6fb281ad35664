#include "bench/line_plot.h"

#include "print/svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace papernet::bench {

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

// A data range mapped onto a pixel range, linear or by log10.
struct Axis {
  double lo = 0, hi = 1;
  bool log = false;
  double from = 0, to = 1;  // pixels
  double operator()(double v) const {
    const double a = log ? std::log10(lo) : lo, b = log ? std::log10(hi) : hi;
    const double t = ((log ? std::log10(v) : v) - a) / (b - a);
    return from + t * (to - from);
  }
};

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) return {0, 1};
  double span = hi - lo;
  if (span <= 0) span = lo != 0 ? std::fabs(lo) : 1;
  const double raw = span / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  const double step = (norm < 1.5 ? 1 : norm < 3 ? 2 : norm < 7 ? 5 : 10) * mag;
  const double first = std::floor(lo / step + 1e-9), last = std::ceil(hi / step - 1e-9);
  std::vector<double> ticks;
  for (double k = first; k <= std::max(last, first + 1); ++k) {
    double v = k * step;
    if (std::fabs(v) < step * 1e-9) v = 0;
    ticks.push_back(v);
  }
  return ticks;
}

std::string tick_label(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", value);
  return buf;
}

std::string write_line_plot(const LinePlot& plot) {
  const double left = 80, right = 24, top = 44, bottom = 96;
  const double w = std::max(100.0, plot.width - left - right);
  const double h = std::max(100.0, plot.height - top - bottom);

  // Ranges from the data.
  double x_min = INFINITY, x_max = -INFINITY, y_min = INFINITY, y_max = -INFINITY;
  for (const PlotSeries& s : plot.series)
    for (const auto& [x, y] : s.points) {
      if (!std::isfinite(x) || !std::isfinite(y) || (plot.log_y && y <= 0)) continue;
      x_min = std::min(x_min, x), x_max = std::max(x_max, x);
      y_min = std::min(y_min, y), y_max = std::max(y_max, y);
    }
  if (!(x_min <= x_max)) x_min = 0, x_max = 1;
  if (!(y_min <= y_max)) y_min = plot.log_y ? 0.1 : 0, y_max = plot.log_y ? 10 : 1;
  if (plot.fix_y) y_min = plot.y_min, y_max = plot.y_max;

  const std::vector<double> xt = nice_ticks(plot.x_from_zero ? 0 : x_min, x_max, 6);
  Axis ax{xt.front(), xt.back(), false, left, left + w};
  std::vector<double> yt;
  Axis ay;
  if (plot.log_y) {
    if (y_min <= 0) y_min = y_max > 0 ? y_max / 10 : 0.1;
    if (y_max <= y_min) y_max = y_min * 10;
    int lo = static_cast<int>(std::floor(std::log10(y_min) + 1e-9));
    int hi = static_cast<int>(std::ceil(std::log10(y_max) - 1e-9));
    if (hi <= lo) hi = lo + 1;
    for (int k = lo; k <= hi; ++k) yt.push_back(std::pow(10.0, k));
    ay = Axis{yt.front(), yt.back(), true, top + h, top};
  } else {
    yt = plot.fix_y ? nice_ticks(y_min, y_max, 5) : nice_ticks(y_min, y_max, 5);
    if (plot.fix_y) {
      yt.erase(std::remove_if(yt.begin(), yt.end(),
                              [&](double v) { return v < y_min - 1e-9 || v > y_max + 1e-9; }),
               yt.end());
      ay = Axis{y_min, y_max, false, top + h, top};
    } else {
      ay = Axis{yt.front(), yt.back(), false, top + h, top};
    }
    if (ay.hi <= ay.lo) ay.hi = ay.lo + 1;
  }

  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << plot.width << "\" height=\""
      << plot.height << "\" viewBox=\"0 0 " << plot.width << " " << plot.height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<defs><clipPath id=\"area\"><rect x=\"" << num(left - 4) << "\" y=\"" << num(top - 4)
      << "\" width=\"" << num(w + 8) << "\" height=\"" << num(h + 8)
      << "\"/></clipPath></defs>\n"  // markers on the frame stay whole
      << "<text x=\"" << num(left + w / 2) << "\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">"
      << xml_escape(plot.title) << "</text>\n";

  // Grid, ticks and tick labels.
  svg << "<g id=\"y-axis\" stroke=\"#ddd\">\n";
  for (double v : yt) {
    const double y = ay(v);
    svg << "<line x1=\"" << num(left) << "\" y1=\"" << num(y) << "\" x2=\"" << num(left + w)
        << "\" y2=\"" << num(y) << "\"/><line x1=\"" << num(left - 5) << "\" y1=\"" << num(y)
        << "\" x2=\"" << num(left) << "\" y2=\"" << num(y) << "\" stroke=\"black\"/><text x=\""
        << num(left - 8) << "\" y=\"" << num(y + 4)
        << "\" text-anchor=\"end\" stroke=\"none\" fill=\"black\">" << tick_label(v) << "</text>\n";
  }
  svg << "</g>\n<g id=\"x-axis\" stroke=\"#ddd\">\n";
  for (double v : xt) {
    const double x = ax(v);
    svg << "<line x1=\"" << num(x) << "\" y1=\"" << num(top) << "\" x2=\"" << num(x) << "\" y2=\""
        << num(top + h) << "\"/><line x1=\"" << num(x) << "\" y1=\"" << num(top + h) << "\" x2=\""
        << num(x) << "\" y2=\"" << num(top + h + 5) << "\" stroke=\"black\"/><text x=\"" << num(x)
        << "\" y=\"" << num(top + h + 19)
        << "\" text-anchor=\"middle\" stroke=\"none\" fill=\"black\">" << tick_label(v)
        << "</text>\n";
  }
  svg << "</g>\n<rect x=\"" << num(left) << "\" y=\"" << num(top) << "\" width=\"" << num(w)
      << "\" height=\"" << num(h) << "\" fill=\"none\" stroke=\"black\"/>\n"
      << "<text x=\"" << num(left + w / 2) << "\" y=\"" << num(top + h + 40)
      << "\" text-anchor=\"middle\">" << xml_escape(plot.x_label) << "</text>\n"
      << "<text transform=\"translate(18 " << num(top + h / 2)
      << ") rotate(-90)\" text-anchor=\"middle\">" << xml_escape(plot.y_label) << "</text>\n";

  // One polyline with markers per series.
  svg << "<g id=\"series\" clip-path=\"url(#area)\" fill=\"none\" stroke-width=\"2.5\">\n";
  for (const PlotSeries& s : plot.series) {
    std::ostringstream pts, marks;  // streams: gcc 12 warns falsely on string + chains
    bool any = false;
    for (const auto& [x, y] : s.points) {
      if (!std::isfinite(x) || !std::isfinite(y) || (plot.log_y && y <= 0)) continue;
      pts << (any ? " " : "") << num(ax(x)) << "," << num(ay(y));
      marks << "<circle cx=\"" << num(ax(x)) << "\" cy=\"" << num(ay(y)) << "\" r=\"3\"/>";
      any = true;
    }
    if (!any) continue;
    svg << "<g stroke=\"" << xml_escape(s.color) << "\" data-series=\"" << xml_escape(s.name)
        << "\"><polyline points=\"" << pts.str() << "\""
        << (s.dashed ? " stroke-dasharray=\"7 4\"" : "") << "/><g fill=\"" << xml_escape(s.color)
        << "\" stroke=\"none\">" << marks.str() << "</g></g>\n";
  }
  svg << "</g>\n";

  // Legend under the axis label, wrapping onto a second row when needed.
  svg << "<g id=\"legend\">\n";
  const double entry = 150, row_y = top + h + 66;
  const int per_row = std::max(1, static_cast<int>((plot.width - 40) / entry));
  const int n = static_cast<int>(plot.series.size());
  for (int i = 0; i < n; ++i) {
    const PlotSeries& s = plot.series[static_cast<std::size_t>(i)];
    const int in_row = std::min(per_row, n - (i / per_row) * per_row);
    const double x0 = plot.width / 2.0 - in_row * entry / 2 + (i % per_row) * entry;
    const double y = row_y + (i / per_row) * 18;
    bool has_points = false;
    for (const auto& [x, yv] : s.points)
      has_points |= std::isfinite(x) && std::isfinite(yv) && !(plot.log_y && yv <= 0);
    svg << "<line x1=\"" << num(x0) << "\" y1=\"" << num(y - 4) << "\" x2=\"" << num(x0 + 26)
        << "\" y2=\"" << num(y - 4) << "\" stroke=\"" << xml_escape(s.color)
        << "\" stroke-width=\"2.5\"" << (s.dashed ? " stroke-dasharray=\"7 4\"" : "")
        << "/><text x=\"" << num(x0 + 32) << "\" y=\"" << num(y) << "\">" << xml_escape(s.name)
        << (has_points ? "" : " (no data)") << "</text>\n";
  }
  svg << "</g>\n</svg>\n";
  return svg.str();
}

}  // namespace papernet::bench
