#include "cropsight/report/svg_charts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "cropsight/report/html_page.hpp"

namespace cropsight::report {

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}
std::string px(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}
double tick_step(double span, int n) {  // 1, 2 or 5 × 10^k, about n ticks over span
  const double raw = span / std::max(1, n);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

}  // namespace

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

  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"cs-chart\" width=\"" + px(W) + "\" height=\"" +
                  px(H) + "\" font-family=\"sans-serif\" font-size=\"11\">";
  if (!o.title.empty())
    s += "<text x=\"" + px(W / 2) + "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">" + html_escape(o.title) +
         "</text>";
  s += "<rect x=\"" + px(left) + "\" y=\"" + px(top) + "\" width=\"" + px(pw) + "\" height=\"" + px(ph) +
       "\" fill=\"none\" stroke=\"#999\"/>";
  const double xs = tick_step(x1 - x0, 6), ys = tick_step(y1 - y0, 5);
  for (double t = std::ceil(x0 / xs) * xs; t <= x1 + 1e-9 * xs; t += xs)
    s += "<line x1=\"" + px(sx(t)) + "\" y1=\"" + px(top) + "\" x2=\"" + px(sx(t)) + "\" y2=\"" + px(top + ph) +
         "\" stroke=\"#eee\"/><text x=\"" + px(sx(t)) + "\" y=\"" + px(top + ph + 16) + "\" text-anchor=\"middle\">" +
         num(t) + "</text>";
  for (double t = std::ceil(y0 / ys) * ys; t <= y1 + 1e-9 * ys; t += ys)
    s += "<line x1=\"" + px(left) + "\" y1=\"" + px(sy(t)) + "\" x2=\"" + px(left + pw) + "\" y2=\"" + px(sy(t)) +
         "\" stroke=\"#eee\"/><text x=\"" + px(left - 6) + "\" y=\"" + px(sy(t) + 4) + "\" text-anchor=\"end\">" +
         num(t) + "</text>";
  if (o.diagonal)
    s += "<line x1=\"" + px(sx(x0)) + "\" y1=\"" + px(sy(x0)) + "\" x2=\"" + px(sx(x1)) + "\" y2=\"" + px(sy(x1)) +
         "\" stroke=\"#888\" stroke-dasharray=\"4 3\"/>";
  if (!o.x_label.empty())
    s += "<text x=\"" + px(left + pw / 2) + "\" y=\"" + px(H - 8) + "\" text-anchor=\"middle\">" +
         html_escape(o.x_label) + "</text>";
  if (!o.y_label.empty())
    s += "<text transform=\"translate(14," + px(top + ph / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
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
      s += "<circle class=\"cs-mark\" cx=\"" + px(sx(ser.x[i])) + "\" cy=\"" + px(sy(ser.y[i])) + "\" r=\"" + px(r) +
           "\" " + paint + "/>";
    }
    if (!ser.name.empty()) {
      s += "<circle cx=\"" + px(left + 10) + "\" cy=\"" + px(legend_y - 4) + "\" r=\"4\" " + paint + "/>";
      s += "<text x=\"" + px(left + 18) + "\" y=\"" + px(legend_y) + "\">" + html_escape(ser.name) + "</text>";
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
                  "\" height=\"" + px(H) + "\" font-family=\"sans-serif\" font-size=\"11\">";
  if (!title.empty())
    s += "<text x=\"" + px(width / 2.0) + "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">" + html_escape(title) +
         "</text>";
  for (std::size_t i = 0; i < bars.size(); ++i) {
    const double y = top + row * double(i);
    const double v = std::isfinite(bars[i].value) ? std::max(0.0, bars[i].value) : 0.0;
    s += "<text x=\"" + px(left - 6) + "\" y=\"" + px(y + 13) + "\" text-anchor=\"end\">" + html_escape(bars[i].label) +
         "</text>";
    s += "<rect class=\"cs-mark\" x=\"" + px(left) + "\" y=\"" + px(y + 3) + "\" width=\"" + px(v / vmax * pw) +
         "\" height=\"" + px(row - 6) + "\" fill=\"#4a8\"/>";
    s += "<text x=\"" + px(left + v / vmax * pw + 4) + "\" y=\"" + px(y + 13) + "\">" + num(bars[i].value) + " " +
         html_escape(unit) + "</text>";
  }
  s += "</svg>";
  return s;
}

}  // namespace cropsight::report
