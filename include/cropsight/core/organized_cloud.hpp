#pragma once
// OrganizedCloud: a point per pixel of a width×height image, structure of arrays.
// Positions in metres in the camera frame (x right, y down, z forward). A pixel without a
// return has NaN in x, y and z. Optional channels are empty vectors when absent.
#include <cmath>
#include <cstdint>
#include <vector>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight {

struct RgbdFrame;

struct OrganizedCloud {
  int width = 0;
  int height = 0;
  std::vector<float> x, y, z;  ///< metres; NaN = no return
  // Optional channels (empty when absent); same indexing as x/y/z.
  std::vector<float> nx, ny, nz;  ///< unit normals; NaN where undefined
  std::vector<float> curvature;   ///< surface variation λ0/(λ0+λ1+λ2); NaN where undefined
  std::vector<Rgb8> color;
  std::vector<std::uint16_t> labels;  ///< ground-truth instance ids, 0 = none

  OrganizedCloud() = default;
  OrganizedCloud(int w, int h);  ///< all points NaN, no optional channels

  std::size_t size() const { return x.size(); }
  bool empty() const { return x.empty(); }
  int index(int u, int v) const { return v * width + u; }
  bool valid(std::size_t i) const { return std::isfinite(z[i]); }
  bool has_normals() const { return !nx.empty(); }
  bool has_color() const { return !color.empty(); }
  bool has_labels() const { return !labels.empty(); }
  Eigen::Vector3f point(std::size_t i) const { return {x[i], y[i], z[i]}; }
  Eigen::Vector3f normal(std::size_t i) const { return {nx[i], ny[i], nz[i]}; }
  std::size_t count_valid() const;
  void allocate_normals();  ///< sizes nx/ny/nz/curvature, filled with NaN
};

/// Deprojects a depth image with the camera intrinsics; depth 0 (no return) and depths outside
/// [min_depth, max_depth] (metres) become NaN. Copies colour and labels when the frame has them.
OrganizedCloud to_organized_cloud(const RgbdFrame& frame, float min_depth = 0.0f, float max_depth = INFINITY);

}  // namespace cropsight
