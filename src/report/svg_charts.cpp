#include "cropsight/report/svg_charts.hpp"

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

std::string svg_scatter_plot(const std::vector<ScatterSeries>& series, const ScatterOptions& o) {
  const double inf = std::numeric_limits<double>::infinity();
  double x0 = inf, x1 = -inf, y0 = inf, y1 = -inf;
  for (const auto& s : series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      const double r = i < s.r.size() && std::isfinite(s.r[i]) ? s.r[i] : 0.0;
      x0 = std::min(x0, s.x[i] - r), x1 = std::max(x1, s.x[i] + r);
      y0 = std::min(y0, s.y[i] - r), y1 = std::max(y1, s.y[i] + r);
    }
  if (!std::isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (o.diagonal) x0 = y0 = std::min(x0, y0), x1 = y1 = std::max(x1, y1);
  if (x1 - x0 < 1e-12) x0 -= 0.5, x1 += 0.5;
  if (y1 - y0 < 1e-12) y0 -= 0.5, y1 += 0.5;
  const double padx = 0.03 * (x1 - x0), pady = 0.03 * (y1 - y0);
  x0 -= padx, x1 += padx, y0 -= pady, y1 += pady;
  const double left = 60, right = 20, top = o.title.empty() ? 15 : 30, bottom = 45;
  double pw = o.width - left - right, ph = o.height - top - bottom;
  if (o.equal_aspect) {  // one scale for both axes: shrink the longer side of the plot area
    const double k = std::min(pw / (x1 - x0), ph / (y1 - y0));
    pw = k * (x1 - x0), ph = k * (y1 - y0);
  }
  const double W = left + pw + right, H = top + ph + bottom;
  auto sx = [&](double x) { return left + (x - x0) / (x1 - x0) * pw; };
  auto sy = [&](double y) { return top + (1.0 - (y - y0) / (y1 - y0)) * ph; };

  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"cs-chart\" width=\"" + svg_pixels(W) +
                  "\" height=\"" + svg_pixels(H) + "\" font-family=\"sans-serif\" font-size=\"11\">";
  if (!o.title.empty())
    s += "<text x=\"" + svg_pixels(W / 2) + "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">" +
         html_escape(o.title) + "</text>";
  s += "<rect x=\"" + svg_pixels(left) + "\" y=\"" + svg_pixels(top) + "\" width=\"" + svg_pixels(pw) + "\" height=\"" +
       svg_pixels(ph) + "\" fill=\"none\" stroke=\"#999\"/>";
  const double xs = tick_step(x1 - x0, 6), ys = tick_step(y1 - y0, 5);
  for (double t = std::ceil(x0 / xs) * xs; t <= x1 + 1e-9 * xs; t += xs)
    s += "<line x1=\"" + svg_pixels(sx(t)) + "\" y1=\"" + svg_pixels(top) + "\" x2=\"" + svg_pixels(sx(t)) +
         "\" y2=\"" + svg_pixels(top + ph) + "\" stroke=\"#eee\"/><text x=\"" + svg_pixels(sx(t)) + "\" y=\"" +
         svg_pixels(top + ph + 16) + "\" text-anchor=\"middle\">" + svg_number(t) + "</text>";
  for (double t = std::ceil(y0 / ys) * ys; t <= y1 + 1e-9 * ys; t += ys)
    s += "<line x1=\"" + svg_pixels(left) + "\" y1=\"" + svg_pixels(sy(t)) + "\" x2=\"" + svg_pixels(left + pw) +
         "\" y2=\"" + svg_pixels(sy(t)) + "\" stroke=\"#eee\"/><text x=\"" + svg_pixels(left - 6) + "\" y=\"" +
         svg_pixels(sy(t) + 4) + "\" text-anchor=\"end\">" + svg_number(t) + "</text>";
  if (o.diagonal)
    s += "<line x1=\"" + svg_pixels(sx(x0)) + "\" y1=\"" + svg_pixels(sy(x0)) + "\" x2=\"" + svg_pixels(sx(x1)) +
         "\" y2=\"" + svg_pixels(sy(x1)) + "\" stroke=\"#888\" stroke-dasharray=\"4 3\"/>";
  if (!o.x_label.empty())
    s += "<text x=\"" + svg_pixels(left + pw / 2) + "\" y=\"" + svg_pixels(H - 8) + "\" text-anchor=\"middle\">" +
         html_escape(o.x_label) + "</text>";
  if (!o.y_label.empty())
    s += "<text transform=\"translate(14," + svg_pixels(top + ph / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
         html_escape(o.y_label) + "</text>";
  const double scale = pw / (x1 - x0);
  double legend_y = top + 14;
  for (const auto& ser : series) {
    const std::string col = html_escape(ser.color);
    const std::string paint = ser.hollow ? "fill=\"none\" stroke=\"" + col + "\" stroke-width=\"1.5\""
                                         : "fill=\"" + col + "\" fill-opacity=\"0.6\" stroke=\"" + col + "\"";
    for (std::size_t i = 0; i < std::min(ser.x.size(), ser.y.size()); ++i) {
      if (!std::isfinite(ser.x[i]) || !std::isfinite(ser.y[i])) continue;
      const double r = i < ser.r.size() && std::isfinite(ser.r[i]) ? std::max(1.5, ser.r[i] * scale) : 3.0;
      s += "<circle class=\"cs-mark\" cx=\"" + svg_pixels(sx(ser.x[i])) + "\" cy=\"" + svg_pixels(sy(ser.y[i])) +
           "\" r=\"" + svg_pixels(r) + "\" " + paint + "/>";
    }
    if (!ser.name.empty()) {
      s += "<circle cx=\"" + svg_pixels(left + 10) + "\" cy=\"" + svg_pixels(legend_y - 4) + "\" r=\"4\" " + paint +
           "/>";
      s += "<text x=\"" + svg_pixels(left + 18) + "\" y=\"" + svg_pixels(legend_y) + "\">" + html_escape(ser.name) +
           "</text>";
      legend_y += 14;
    }
  }
  s += "</svg>";
  return s;
}

std::string svg_bar_chart(const std::vector<Bar>& bars, const std::string& title, const std::string& unit, int width) {
  const double left = 140, right = 80, top = title.empty() ? 10 : 30, row = 20;
  const double H = top + row * double(bars.size()) + 10, pw = width - left - right;
  double vmax = 0;
  for (const auto& b : bars)
    if (std::isfinite(b.value)) vmax = std::max(vmax, b.value);
  if (vmax <= 0) vmax = 1;
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"cs-chart\" width=\"" + std::to_string(width) +
                  "\" height=\"" + svg_pixels(H) + "\" font-family=\"sans-serif\" font-size=\"11\">";
  if (!title.empty())
    s += "<text x=\"" + svg_pixels(width / 2.0) + "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">" +
         html_escape(title) + "</text>";
  for (std::size_t i = 0; i < bars.size(); ++i) {
    const double y = top + row * double(i);
    const double v = std::isfinite(bars[i].value) ? std::max(0.0, bars[i].value) : 0.0;
    s += "<text x=\"" + svg_pixels(left - 6) + "\" y=\"" + svg_pixels(y + 13) + "\" text-anchor=\"end\">" +
         html_escape(bars[i].label) + "</text>";
    s += "<rect class=\"cs-mark\" x=\"" + svg_pixels(left) + "\" y=\"" + svg_pixels(y + 3) + "\" width=\"" +
         svg_pixels(v / vmax * pw) + "\" height=\"" + svg_pixels(row - 6) + "\" fill=\"#4a8\"/>";
    s += "<text x=\"" + svg_pixels(left + v / vmax * pw + 4) + "\" y=\"" + svg_pixels(y + 13) + "\">" +
         svg_number(bars[i].value) + " " + html_escape(unit) + "</text>";
  }
  s += "</svg>";
  return s;
}

}  // namespace cropsight::report
