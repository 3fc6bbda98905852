#pragma once
// A 2D detector's output and the one interface every 2D detector implements: the potato
// pipeline's classical (colour and range foreground) and ONNX (OpenCV DNN) backends, and the
// project's own CNN detector. A pipeline holds a Detector2D chosen by its preset and
// never knows which backend it runs.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "cropsight/core/box2d.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight {

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
