#pragma once
// A small SVG line-plot writer for the benchmark report: no external plotting tool.

#include <string>
#include <utility>
#include <vector>

namespace papernet::bench {

/// One line of a plot: its points in data coordinates, drawn in the order given.
struct PlotSeries {
  std::string name;     ///< legend text
  std::string color;    ///< any SVG colour, e.g. "#1f77b4"
  bool dashed = false;  ///< dashed line (e.g. the paper's figures next to ours)
  std::vector<std::pair<double, double>> points;
};

/// A plot of lines against a shared x axis. Axis ranges come from the data unless fixed.
struct LinePlot {
  std::string title, x_label, y_label;
  bool log_y = false;  ///< logarithmic y axis (points with y <= 0 are left out)
  bool fix_y = false;  ///< use [y_min, y_max] instead of the data's range
  double y_min = 0, y_max = 1;
  bool x_from_zero = true;  ///< the x axis starts at 0 (face counts), else at the data's minimum
  int width = 720, height = 440;  ///< pixels
  std::vector<PlotSeries> series;
};

/// Round tick values covering [lo, hi] (about `target` of them, steps of 1, 2 or 5 x 10^k).
/// \pre lo <= hi
std::vector<double> nice_ticks(double lo, double hi, int target);

/// A tick label: shortest of %g-style text, no exponent for 1e-4..1e6.
std::string tick_label(double value);

/// The plot as a standalone SVG document (axes with ticks and labels, a grid, one polyline with
/// point markers per series, a legend under the plot). Series without points are left out of the
/// drawing but kept in the legend, marked "(no data)". Never throws on odd data: empty or
/// non-finite input gives a plot with a default range.
std::string write_line_plot(const LinePlot& plot);

}  // namespace papernet::bench
