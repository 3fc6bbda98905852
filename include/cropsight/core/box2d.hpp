#pragma once
// A 2D detector's box (Detection2D) and its IoU: plain C++17, so that results holding boxes reach
// the ROS nodes (built as C++17) as they are. The detector interface is detection2d.hpp.
#include <algorithm>

namespace cropsight {

/// One box found in an image. Image frame: x right, y down, pixels; continuous coordinates, so
/// the box covers [x1, x2) x [y1, y2) and pixel (u, v) spans [u, u + 1) x [v, v + 1). Text files
/// in the paper's format ("potato score x1 y1 x2 y2") store the corners as they are.
struct Detection2D {
  float x1 = 0, y1 = 0, x2 = 0, y2 = 0;
  int class_id = 0;  ///< index into the detector's class_names()
  float score = 0;   ///< confidence in [0, 1]; higher = more confident

  float width() const { return x2 - x1; }
  float height() const { return y2 - y1; }
  float centre_x() const { return 0.5f * (x1 + x2); }
  float centre_y() const { return 0.5f * (y1 + y2); }
  float area() const { return width() > 0 && height() > 0 ? width() * height() : 0.f; }
};

/// Intersection over union of two continuous boxes (0 when either is empty).
inline float iou(const Detection2D& a, const Detection2D& b) {
  const float w = std::min(a.x2, b.x2) - std::max(a.x1, b.x1), h = std::min(a.y2, b.y2) - std::max(a.y1, b.y1);
  const float inter = w > 0 && h > 0 ? w * h : 0.f;
  const float uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0.f;
}

}  // namespace cropsight
