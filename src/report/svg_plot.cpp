#include "cropsight/report/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "cropsight/report/html_page.hpp"
#include "number_format.hpp"

namespace cropsight::report {

using detail::svg_number;
using detail::svg_pixels;
using detail::tick_step;

std::string svg_line_plot(const std::vector<Series>& series, const PlotOptions& o) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const auto& s : series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x0 = std::min(x0, s.x[i]);
      x1 = std::max(x1, s.x[i]);
      y0 = std::min(y0, s.y[i]);
      y1 = std::max(y1, s.y[i]);
    }
  if (!std::isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (o.y_from_zero) y0 = std::min(y0, 0.0), y1 = std::max(y1, 0.0);
  if (x1 - x0 < 1e-12) x0 -= 0.5, x1 += 0.5;
  if (y1 - y0 < 1e-12) y0 -= 0.5, y1 += 0.5;
  const double left = 60, right = 20, top = o.title.empty() ? 15 : 30, bottom = 45;
  const double pw = o.width - left - right, ph = o.height - top - bottom;
  auto sx = [&](double x) { return left + (x - x0) / (x1 - x0) * pw; };
  auto sy = [&](double y) { return top + (1.0 - (y - y0) / (y1 - y0)) * ph; };

  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(o.width) + "\" height=\"" +
                  std::to_string(o.height) + "\" font-family=\"sans-serif\" font-size=\"11\">";
  if (!o.title.empty())
    s += "<text x=\"" + svg_pixels(o.width / 2.0) + "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">" +
         html_escape(o.title) + "</text>";
  s += "<rect x=\"" + svg_pixels(left) + "\" y=\"" + svg_pixels(top) + "\" width=\"" + svg_pixels(pw) + "\" height=\"" +
       svg_pixels(ph) + "\" fill=\"none\" stroke=\"#999\"/>";
  const double xs = tick_step(x1 - x0, 6), ys = tick_step(y1 - y0, 5);
  for (double t = std::ceil(x0 / xs) * xs; t <= x1 + 1e-9 * xs; t += xs)
    s += "<line x1=\"" + svg_pixels(sx(t)) + "\" y1=\"" + svg_pixels(top + ph) + "\" x2=\"" + svg_pixels(sx(t)) +
         "\" y2=\"" + svg_pixels(top + ph + 4) + "\" stroke=\"#999\"/><text x=\"" + svg_pixels(sx(t)) + "\" y=\"" +
         svg_pixels(top + ph + 16) + "\" text-anchor=\"middle\">" + svg_number(t) + "</text>";
  for (double t = std::ceil(y0 / ys) * ys; t <= y1 + 1e-9 * ys; t += ys)
    s += "<line x1=\"" + svg_pixels(left) + "\" y1=\"" + svg_pixels(sy(t)) + "\" x2=\"" + svg_pixels(left + pw) +
         "\" y2=\"" + svg_pixels(sy(t)) + "\" stroke=\"#eee\"/><text x=\"" + svg_pixels(left - 6) + "\" y=\"" +
         svg_pixels(sy(t) + 4) + "\" text-anchor=\"end\">" + svg_number(t) + "</text>";
  if (!o.x_label.empty())
    s += "<text x=\"" + svg_pixels(left + pw / 2) + "\" y=\"" + svg_pixels(o.height - 8.0) +
         "\" text-anchor=\"middle\">" + html_escape(o.x_label) + "</text>";
  if (!o.y_label.empty())
    s += "<text transform=\"translate(14," + svg_pixels(top + ph / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
         html_escape(o.y_label) + "</text>";
  double legend_y = top + 14;
  for (const auto& ser : series) {
    std::string pts;
    for (std::size_t i = 0; i < std::min(ser.x.size(), ser.y.size()); ++i)
      if (std::isfinite(ser.x[i]) && std::isfinite(ser.y[i]))
        pts += svg_pixels(sx(ser.x[i])) + "," + svg_pixels(sy(ser.y[i])) + " ";
    s += "<polyline fill=\"none\" stroke=\"" + html_escape(ser.color) + "\" stroke-width=\"1.8\" points=\"" + pts +
         "\"/>";
    if (!ser.name.empty()) {
      s += "<line x1=\"" + svg_pixels(left + pw - 110) + "\" y1=\"" + svg_pixels(legend_y - 4) + "\" x2=\"" +
           svg_pixels(left + pw - 92) + "\" y2=\"" + svg_pixels(legend_y - 4) + "\" stroke=\"" +
           html_escape(ser.color) + "\" stroke-width=\"2\"/>";
      s += "<text x=\"" + svg_pixels(left + pw - 88) + "\" y=\"" + svg_pixels(legend_y) + "\">" +
           html_escape(ser.name) + "</text>";
      legend_y += 14;
    }
  }
  s += "</svg>";
  return s;
}

}  // namespace cropsight::report
