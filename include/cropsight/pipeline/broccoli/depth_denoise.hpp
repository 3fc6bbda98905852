#pragma once
// Noise-adaptive depth denoising for the broccoli detector: a ToF camera in direct sun
// (or far from a dark surface) returns depth with several times its usual noise; OES's neighbour
// tolerance (millimetres) then breaks every surface into debris and no head is a cluster. The
// frame's noise is estimated from the depth itself, and only a noisy frame is smoothed, by an
// edge-preserving bilateral filter whose range sigma follows the estimate: depth jumps between a
// head and the leaves below it are many sigmas and survive, the per-pixel noise does not.
#include <cstdint>
#include <span>
#include <vector>

#include "cropsight/core/config.hpp"

namespace cropsight::pipeline::broccoli {

struct DepthDenoiseConfig {
  float above = 0.0f;         ///< m; frames whose noise estimate exceeds this are filtered (0 = off)
  float sigma_factor = 3.0f;  ///< bilateral range sigma = this x the noise estimate
  int diameter = 5;           ///< px; bilateral window
  float sigma_space = 2.0f;   ///< px; bilateral spatial sigma
  bool in_training = true;    ///< false: `train` builds its samples from the raw frames

  template <class V>
  void visit(V& v) {
    v("above", above,
      "m; when > 0, a frame whose depth noise estimate (robust sigma of the row second differences inside the "
      "depth window) exceeds this is smoothed by a bilateral filter before the cloud is made (ours: "
      "ToF in direct sun; 0 = off, the paper's raw depth)",
      Range::at_least(0.0));
    v("sigma_factor", sigma_factor, "bilateral range sigma in units of the frame's noise estimate (ours)",
      Range::above(0.0));
    v("diameter", diameter, "px; bilateral filter window (ours; cv::bilateralFilter's d)", Range::within(3, 15));
    v("sigma_space", sigma_space, "px; bilateral spatial sigma (ours)", Range::above(0.0));
    v("in_training", in_training,
      "denoise the training frames too (true), or only the frames detected on (false: the samples of `train "
      "broccoli` come from the raw frames; measured on validation for the general model, "
      "docs/pipelines/broccoli-heads.md)");
  }
};

/// Robust noise sigma (m) of a 16-bit depth image (`width`·`height` values, metres = value·scale, 0
/// = no return): 1.4826 · median |z(u-1) - 2 z(u) + z(u+1)| / sqrt(6) over every fourth row, using
/// only triples whose three depths lie in [min_depth, max_depth]. A plane has no second difference,
/// so the estimate is the noise (plus the curvature of the surfaces, small at the pixel scale).
/// NaN with fewer than 1000 such triples. Uses a histogram of 0.25 mm bins (no sort).
float estimate_depth_noise(std::span<const std::uint16_t> depth, int width, int height, float scale, float min_depth,
                           float max_depth, std::vector<std::uint32_t>& histogram);

/// cv::bilateralFilter of the depth in metres (range sigma `sigma_color` m), written back as 16-bit
/// values into `out`; pixels without a return stay 0 (their 0 m is many range sigmas from any
/// surface, so it never leaks into a valid neighbour). Throws Error("depth denoise", ...) for a
/// size mismatch or bad parameters.
void bilateral_depth(std::span<const std::uint16_t> depth, int width, int height, float scale, float sigma_color,
                     int diameter, float sigma_space, std::vector<std::uint16_t>& out);

}  // namespace cropsight::pipeline::broccoli
