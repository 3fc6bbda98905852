#pragma once
// The four classic Middlebury pairs (../shared/data/middlebury/) and the bad-pixel metric.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "cropsight/core/image.hpp"
#include "cropsight/stereo/disparity.hpp"

namespace cropsight::stereo {

struct MiddleburyPair {
  std::string name;
  ColorImage left, right;
  DisparityImage truth;   ///< pixels, NaN where the ground truth is unknown
  int max_disparity = 0;  ///< largest true disparity (data README)
};

/// Loads tsukuba, venus, teddy and cones from `dir` (each a folder with left.png, right.png and
/// disp_left.pgm / disp_left.png). Throws Error(file, ...) for a missing or unreadable file, images
/// that are not 8-bit or differ in size or kind (grey / colour), a ground truth that is not 8-bit
/// or has no valid (non-zero) pixel.
std::vector<MiddleburyPair> load_middlebury(const std::filesystem::path& dir);

struct BadPixelStats {
  double bad1 = 0;     ///< percent of ground-truth pixels with |d - d_true| > 1 or no estimate
  double bad2 = 0;     ///< same with threshold 2
  double invalid = 0;  ///< percent of ground-truth pixels without estimate
  long pixels = 0;     ///< ground-truth pixels counted
};

/// Bad-pixel rates over every pixel with ground truth; NaN estimates count as errors.
/// Sizes must agree and the truth must have a valid pixel, else Error(where, ...).
BadPixelStats bad_pixels(const DisparityImage& estimate, const DisparityImage& truth,
                         const std::string& where = "disparity");

/// One matcher's scores on the Middlebury pairs (eval stereo).
struct MiddleburyPairResult {
  std::string name;
  BadPixelStats stats;
  double ms = 0;            ///< the matcher's wall time on this pair
  int num_disparities = 0;  ///< search range it was given
};
struct MiddleburyEvaluation {
  std::vector<MiddleburyPairResult> pairs;
  double mean_bad1 = 0, mean_bad2 = 0;  ///< percent, mean over the pairs
};

/// A matcher under test: the pair and the search range to use.
using MiddleburyMatcher = std::function<DisparityImage(const MiddleburyPair& pair, int num_disparities)>;

/// Runs `match` on every pair with the pair's true range rounded up to a multiple of 16 (largest
/// true disparity + 1) as search range, timing it, and scores it with bad_pixels().
MiddleburyEvaluation evaluate_middlebury(const std::vector<MiddleburyPair>& pairs, const MiddleburyMatcher& match);

}  // namespace cropsight::stereo
