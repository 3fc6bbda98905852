#include "cropsight/report/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "cropsight/report/html_page.hpp"

namespace cropsight::report {

namespace {
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.4g", v);
  return buf;
}
std::string px(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f", v);
  return buf;
}
/// "Nice" tick step (1, 2 or 5 times a power of ten) giving about `n` ticks over `span`.
double tick_step(double span, int n) {
  const double raw = span / std::max(1, n);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}
}  // namespace

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
    s += "<text x=\"" + px(o.width / 2.0) + "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">" +
         html_escape(o.title) + "</text>";
  s += "<rect x=\"" + px(left) + "\" y=\"" + px(top) + "\" width=\"" + px(pw) + "\" height=\"" + px(ph) +
       "\" fill=\"none\" stroke=\"#999\"/>";
  const double xs = tick_step(x1 - x0, 6), ys = tick_step(y1 - y0, 5);
  for (double t = std::ceil(x0 / xs) * xs; t <= x1 + 1e-9 * xs; t += xs)
    s += "<line x1=\"" + px(sx(t)) + "\" y1=\"" + px(top + ph) + "\" x2=\"" + px(sx(t)) + "\" y2=\"" +
         px(top + ph + 4) + "\" stroke=\"#999\"/><text x=\"" + px(sx(t)) + "\" y=\"" + px(top + ph + 16) +
         "\" text-anchor=\"middle\">" + num(t) + "</text>";
  for (double t = std::ceil(y0 / ys) * ys; t <= y1 + 1e-9 * ys; t += ys)
    s += "<line x1=\"" + px(left) + "\" y1=\"" + px(sy(t)) + "\" x2=\"" + px(left + pw) + "\" y2=\"" + px(sy(t)) +
         "\" stroke=\"#eee\"/><text x=\"" + px(left - 6) + "\" y=\"" + px(sy(t) + 4) + "\" text-anchor=\"end\">" +
         num(t) + "</text>";
  if (!o.x_label.empty())
    s += "<text x=\"" + px(left + pw / 2) + "\" y=\"" + px(o.height - 8.0) + "\" text-anchor=\"middle\">" +
         html_escape(o.x_label) + "</text>";
  if (!o.y_label.empty())
    s += "<text transform=\"translate(14," + px(top + ph / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
         html_escape(o.y_label) + "</text>";
  double legend_y = top + 14;
  for (const auto& ser : series) {
    std::string pts;
    for (std::size_t i = 0; i < std::min(ser.x.size(), ser.y.size()); ++i)
      if (std::isfinite(ser.x[i]) && std::isfinite(ser.y[i])) pts += px(sx(ser.x[i])) + "," + px(sy(ser.y[i])) + " ";
    s += "<polyline fill=\"none\" stroke=\"" + html_escape(ser.color) + "\" stroke-width=\"1.8\" points=\"" + pts +
         "\"/>";
    if (!ser.name.empty()) {
      s += "<line x1=\"" + px(left + pw - 110) + "\" y1=\"" + px(legend_y - 4) + "\" x2=\"" + px(left + pw - 92) +
           "\" y2=\"" + px(legend_y - 4) + "\" stroke=\"" + html_escape(ser.color) + "\" stroke-width=\"2\"/>";
      s += "<text x=\"" + px(left + pw - 88) + "\" y=\"" + px(legend_y) + "\">" + html_escape(ser.name) + "</text>";
      legend_y += 14;
    }
  }
  s += "</svg>";
  return s;
}

}  // namespace cropsight::report
