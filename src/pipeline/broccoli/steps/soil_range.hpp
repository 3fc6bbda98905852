#pragma once
// The range-aware options of the cloud step (RangeConfig, cloud_step.hpp): the soil's depth read
// off a frame's depth histogram, and the OES thresholds scaled to the range the heads lie at.
#include <cstdint>
#include <vector>

#include "cropsight/segmentation/organized_clustering.hpp"

namespace cropsight::pipeline::broccoli::steps {

/// The `fraction` percentile of the valid (non-zero) raw depths of a width x height image, in
/// metres (raw · scale), from a histogram of 5 mm bins (`hist`, reused) over every 4th row; NaN
/// with fewer than 1000 valid pixels in the frame (estimated from the rows read).
float depth_percentile(const std::vector<std::uint16_t>& depth, int width, int height, float scale, float fraction,
                       std::vector<std::uint32_t>& hist);

/// `oes` for surfaces `s` times as far as the range it was set for: point counts (min_size,
/// min_size_border, max_size; 0 stays 0) divided by s², distance_tolerance multiplied by s.
segmentation::OesConfig oes_at_range(const segmentation::OesConfig& oes, float s);

}  // namespace cropsight::pipeline::broccoli::steps
