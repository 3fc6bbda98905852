#pragma once
// The cloud step's hot loop (cloud_step.hpp): deprojection of a depth image through per-pixel ray
// slopes, with the depth window applied in the same pass. Its own file because it is compiled
// with -O3 and -ffp-contract=off (src/pipeline/CMakeLists.txt) for its AVX2 / AVX-512 clones.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cropsight/core/camera.hpp"

namespace cropsight::pipeline::broccoli::steps {

/// Per pixel (u - cx) / fx into `rx` and (v - cy) / fy into `ry` (width · height values each, row
/// major), computed in double and rounded once, as CameraIntrinsics::deproject does.
void ray_slopes(const CameraIntrinsics& camera, std::vector<float>& rx, std::vector<float>& ry);

/// Deprojection and the depth window of n pixels: Z = d · scale (m), NaN when d = 0 or Z lies
/// outside [lo, hi] (m); X = rx · Z, Y = ry · Z. The same float values as deprojecting and then
/// calling geometry::filter_depth_range: every lane does the scalar loop's operations, no FMA
/// (tests/pipeline checks the cloud against that loop). The output arrays hold n values each and
/// do not overlap the inputs.
void deproject_depth(std::size_t n, const std::uint16_t* d, const float* rx, const float* ry, float scale, float lo,
                     float hi, float* X, float* Y, float* Z);

}  // namespace cropsight::pipeline::broccoli::steps
