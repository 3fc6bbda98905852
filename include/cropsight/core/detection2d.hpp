#pragma once
// A 2D detector's output and the one interface every 2D detector implements: the potato
// pipeline's classical (colour and range foreground) and ONNX (OpenCV DNN) backends, and the
// project's own CNN detector. A pipeline holds a Detector2D chosen by its preset and
// never knows which backend it runs.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "cropsight/core/image.hpp"

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

/// What a detector sees of one frame: the colour image and, when the input has it, depth in
/// metres registered to the colour image (0 = no depth). `depth_m` may be null or empty.
struct DetectorInput {
  const ColorImage* image = nullptr;
  const Image<float>* depth_m = nullptr;
};

/// Every 2D detector. Not thread-safe: detect() may reuse buffers between calls; use one
/// detector per thread. Errors (an image the backend cannot take) throw cropsight::Error.
class Detector2D {
 public:
  virtual ~Detector2D() = default;
  /// Boxes found in `in`, highest score first, every score >= the backend's threshold.
  virtual std::vector<Detection2D> detect(const DetectorInput& in) = 0;
  /// The class names, indexed by Detection2D::class_id.
  virtual std::vector<std::string> class_names() const = 0;
};

}  // namespace cropsight
