#pragma once
// Inline-SVG scatter plots (with optional data-unit circles: field maps) and horizontal bar
// charts, complementing svg_line_plot (svg_plot.hpp). No JavaScript, no external assets. Every
// chart is one "<svg class="cs-chart" ...>" element whose data marks carry class "cs-mark", so a
// test (or a reader's browser) can count what was drawn.
#include <string>
#include <vector>

namespace cropsight::report {

struct ScatterSeries {
  std::string name;
  std::vector<double> x, y;  ///< same length; non-finite points are skipped
  std::vector<double> r;     ///< optional: circle radius per point in x-axis data units (field maps)
  std::string color = "#2a7";
  bool hollow = false;  ///< outline only (e.g. ground truth under estimates)
};

struct ScatterOptions {
  std::string title, x_label, y_label;
  int width = 560, height = 360;
  bool equal_aspect = false;  ///< same scale on both axes (maps)
  bool diagonal = false;      ///< draw y = x (estimate against truth)
};

std::string svg_scatter_plot(const std::vector<ScatterSeries>& series, const ScatterOptions& options);

struct Bar {
  std::string label;
  double value = 0.0;
};

/// Horizontal bars, one per entry, with the value printed after each bar (`unit` appended).
std::string svg_bar_chart(const std::vector<Bar>& bars, const std::string& title, const std::string& unit,
                          int width = 560);

}  // namespace cropsight::report
