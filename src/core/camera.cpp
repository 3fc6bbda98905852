#include "cropsight/core/camera.hpp"

#include <cmath>

#include "cropsight/core/error.hpp"

namespace cropsight {

CameraIntrinsics CameraIntrinsics::from_fov(int width, int height, double hfov_rad, double vfov_rad) {
  CameraIntrinsics c;
  c.width = width;
  c.height = height;
  c.fx = 0.5 * width / std::tan(0.5 * hfov_rad);
  c.fy = 0.5 * height / std::tan(0.5 * vfov_rad);
  c.cx = 0.5 * (width - 1);
  c.cy = 0.5 * (height - 1);
  return c;
}

void CameraIntrinsics::validate(const std::string& where) const {
  if (width <= 0 || height <= 0)
    throw Error(where, "image size must be positive, got " + std::to_string(width) + "x" + std::to_string(height));
  if (!(std::isfinite(fx) && std::isfinite(fy) && fx > 0 && fy > 0))
    throw Error(where, "focal lengths fx, fy must be finite and positive");
  if (!(std::isfinite(cx) && std::isfinite(cy))) throw Error(where, "principal point cx, cy must be finite");
  // Generous bounds (a cropped sensor may put it off-centre, not a width away): catches unit and
  // typing errors such as 1e308.
  if (!(cx >= -double(width) && cx <= 2.0 * double(width) && cy >= -double(height) && cy <= 2.0 * double(height)))
    throw Error(where, "principal point (" + std::to_string(cx) + ", " + std::to_string(cy) +
                           ") lies more than an image size outside the " + std::to_string(width) + "x" +
                           std::to_string(height) + " image");
  if (!(std::isfinite(depth_scale) && depth_scale > 0))
    throw Error(where, "depth_scale must be finite and positive (metres per depth unit)");
  for (double d : distortion)
    if (!std::isfinite(d)) throw Error(where, "distortion coefficients must be finite");
}

}  // namespace cropsight
