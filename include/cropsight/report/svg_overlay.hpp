#pragma once
// An image with vector marks over it (boxes, axes, crosses, labels), as one inline <svg> holding
// the image as an embedded PNG: the marks and their text stay sharp at any zoom, where marks drawn
// into the pixels blur. Nothing is fetched: the page stays self-contained (html_page.hpp).
//
// Coordinates are the image's pixels: x right, y down, (0, 0) the top-left corner of the first
// pixel, so pixel (u, v) covers [u, u + 1) x [v, v + 1). Colours are any CSS colour ("#2a7",
// "white"); text is escaped.
#include <string>

#include "cropsight/core/image.hpp"

namespace cropsight::report {

class SvgOverlay {
 public:
  /// `display_width` in CSS pixels (0 = the image's width); the SVG scales to narrow screens.
  explicit SvgOverlay(const ColorImage& image, int display_width = 0);

  void rect(double x1, double y1, double x2, double y2, const std::string& color, double stroke = 2,
            bool dashed = false);
  void line(double x1, double y1, double x2, double y2, const std::string& color, double stroke = 2);
  void circle(double cx, double cy, double r, const std::string& color, double stroke = 2);
  /// An upright cross of half-size `half` centred on (x, y).
  void cross(double x, double y, double half, const std::string& color, double stroke = 2);
  /// Text whose baseline starts at (x, y), with a dark halo so that it reads on any background.
  void text(double x, double y, const std::string& text, const std::string& color, double size = 14);

  int width() const { return width_; }
  int height() const { return height_; }
  /// "<svg class="overlay" ...>...</svg>".
  std::string svg() const;

 private:
  int width_ = 0, height_ = 0, display_width_ = 0;
  std::string png_, marks_;
};

}  // namespace cropsight::report
