#include "cropsight/report/svg_overlay.hpp"

#include <algorithm>

#include "cropsight/io/image_io.hpp"
#include "cropsight/report/html_page.hpp"
#include "number_format.hpp"

namespace cropsight::report {

namespace {
// Coordinates with two decimals: sub-pixel placement without 17-digit noise in the page.
std::string num(double v) { return detail::format_number(v, "%.2f"); }
std::string stroke_of(const std::string& color, double width) {
  return " fill=\"none\" stroke=\"" + html_escape(color) + "\" stroke-width=\"" + num(width) + "\"";
}
}  // namespace

SvgOverlay::SvgOverlay(const ColorImage& image, int display_width)
    : width_(image.width),
      height_(image.height),
      display_width_(display_width > 0 ? display_width : image.width),
      png_(io::encode_png(image)) {}

void SvgOverlay::rect(double x1, double y1, double x2, double y2, const std::string& color, double stroke,
                      bool dashed) {
  marks_ += "<rect x=\"" + num(x1) + "\" y=\"" + num(y1) + "\" width=\"" + num(x2 - x1) + "\" height=\"" +
            num(y2 - y1) + "\"" + stroke_of(color, stroke) + (dashed ? " stroke-dasharray=\"6 4\"" : "") + "/>";
}

void SvgOverlay::line(double x1, double y1, double x2, double y2, const std::string& color, double stroke) {
  marks_ += "<line x1=\"" + num(x1) + "\" y1=\"" + num(y1) + "\" x2=\"" + num(x2) + "\" y2=\"" + num(y2) + "\"" +
            stroke_of(color, stroke) + " stroke-linecap=\"round\"/>";
}

void SvgOverlay::circle(double cx, double cy, double r, const std::string& color, double stroke) {
  marks_ +=
      "<circle cx=\"" + num(cx) + "\" cy=\"" + num(cy) + "\" r=\"" + num(r) + "\"" + stroke_of(color, stroke) + "/>";
}

void SvgOverlay::cross(double x, double y, double half, const std::string& color, double stroke) {
  line(x - half, y, x + half, y, color, stroke);
  line(x, y - half, x, y + half, color, stroke);
}

void SvgOverlay::text(double x, double y, const std::string& content, const std::string& color, double size) {
  marks_ += "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + num(size) + "\" fill=\"" +
            html_escape(color) +
            "\" stroke=\"#000\" stroke-width=\"3\" paint-order=\"stroke\" "
            "font-family=\"system-ui,sans-serif\">" +
            html_escape(content) + "</text>";
}

std::string SvgOverlay::svg() const {
  const std::string w = std::to_string(width_), h = std::to_string(height_);
  const std::string display_h = std::to_string(int(double(display_width_) * height_ / std::max(1, width_) + 0.5));
  return "<svg class=\"overlay\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " + w + " " + h + "\" width=\"" +
         std::to_string(display_width_) + "\" height=\"" + display_h + "\"><image width=\"" + w + "\" height=\"" + h +
         "\" href=\"" + png_data_uri(png_) + "\"/>" + marks_ + "</svg>";
}

}  // namespace cropsight::report
