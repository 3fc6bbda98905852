#pragma once
// Number formatting shared by the report's pages and SVG plots: one copy (sequence_page,
// broccoli_report, svg_plot and svg_charts each had their own; unity builds, which compile them
// as one translation unit, found the copies).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace cropsight::report::detail {

/// `v` printed with a printf format holding one floating-point conversion ("%.3f").
inline std::string format_number(double v, const char* printf_format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, v);
  return buf;
}

/// SVG coordinates and labels: 4 significant digits for values, 0.1 px for positions.
inline std::string svg_number(double v) { return format_number(v, "%.4g"); }
inline std::string svg_pixels(double v) { return format_number(v, "%.1f"); }

/// "Nice" tick step (1, 2 or 5 times a power of ten) giving about `n` ticks over `span`.
inline double tick_step(double span, int n) {
  const double raw = span / std::max(1, n);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

}  // namespace cropsight::report::detail
