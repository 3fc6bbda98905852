#pragma once
// Minimal inline-SVG plots for HTML reports (no JavaScript, no external assets).
#include <string>
#include <vector>

namespace cropsight::report {

struct Series {
  std::string name;
  std::vector<double> x, y;    ///< same length; non-finite points are skipped
  std::string color = "#2a7";  ///< any CSS colour
};

struct PlotOptions {
  std::string title, x_label, y_label;
  int width = 560, height = 300;  ///< pixels
  bool y_from_zero = false;       ///< include 0 in the y axis range
};

/// A line plot of one or more series with axes, ticks and a legend. Returns "<svg ...>...</svg>".
std::string svg_line_plot(const std::vector<Series>& series, const PlotOptions& options);

}  // namespace cropsight::report
