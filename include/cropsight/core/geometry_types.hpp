#pragma once
// Small value types shared by detections, segments and measurements. C++17, so that results
// holding them reach the ROS nodes (built as C++17) as they are.
#include <algorithm>

namespace cropsight {

/// Axis-aligned box in pixels: x, y = top-left column/row (inclusive), width/height in pixels.
struct Box2D {
  int x = 0, y = 0, width = 0, height = 0;
  int area() const { return width * height; }
  bool empty() const { return width <= 0 || height <= 0; }
  friend bool operator==(const Box2D& a, const Box2D& b) {
    return a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height;
  }
  friend bool operator!=(const Box2D& a, const Box2D& b) { return !(a == b); }
};

/// Intersection over union of two pixel boxes (0 when either is empty).
inline double iou(const Box2D& a, const Box2D& b) {
  const int x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
  const int x1 = std::min(a.x + a.width, b.x + b.width), y1 = std::min(a.y + a.height, b.y + b.height);
  const int inter = std::max(0, x1 - x0) * std::max(0, y1 - y0);
  const int uni = a.area() + b.area() - inter;
  return uni > 0 ? double(inter) / uni : 0.0;
}

}  // namespace cropsight
