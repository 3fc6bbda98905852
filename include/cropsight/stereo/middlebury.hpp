#pragma once
// Stereo pairs with ground truth and the bad-pixel metric: the four classic Middlebury pairs
// (../shared/data/middlebury/, load_middlebury) and any scene folder (stereo_scenes.hpp).
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
  /// Search range the matcher gets: a multiple of 16 (0 = from max_disparity, as
  /// evaluate_middlebury() documents).
  int num_disparities = 0;
  /// 255 where the left pixel is visible in the right view (non-occluded), 0 elsewhere; empty when
  /// the scene has no right-view ground truth (or occlusion mask), so no non-occluded score.
  GrayImage nonoccluded;
};

/// Loads tsukuba, venus, teddy and cones from `dir` (each a folder with left.png, right.png and
/// disp_left.pgm / disp_left.png). Throws Error(file, ...) for a missing or unreadable file, images
/// that are not 8-bit or differ in size or kind (grey / colour), a ground truth that is not 8-bit
/// or has no valid (non-zero) pixel.
std::vector<MiddleburyPair> load_middlebury(const std::filesystem::path& dir);

struct BadPixelStats {
  double bad1 = 0;       ///< percent of ground-truth pixels with |d - d_true| > 1 or no estimate
  double bad2 = 0;       ///< same with threshold 2
  double invalid = 0;    ///< percent of ground-truth pixels without estimate (holes)
  double avg_error = 0;  ///< px; mean |d - d_true| over the ground-truth pixels with an estimate
  long pixels = 0;       ///< ground-truth pixels counted
};

/// Bad-pixel rates over every pixel with ground truth; NaN estimates count as errors. With a
/// non-empty `mask` (same size) only pixels where it is non-zero count. Sizes must agree and
/// the truth must have a valid pixel (inside the mask), else Error(where, ...).
BadPixelStats bad_pixels(const DisparityImage& estimate, const DisparityImage& truth,
                         const std::string& where = "disparity", const GrayImage& mask = {});

/// Non-occluded mask of the left view from the two views' ground truths (pixels): 255 where the
/// left truth d is known and the right truth at x - d (rounded) is known and within `tolerance`
/// of d, 0 elsewhere. Sizes must agree, else Error(where, ...).
GrayImage nonoccluded_mask(const DisparityImage& left_truth, const DisparityImage& right_truth, double tolerance = 1.0,
                           const std::string& where = "disparity");

/// One matcher's scores on the Middlebury pairs (eval stereo).
struct MiddleburyPairResult {
  std::string name;
  BadPixelStats stats;
  bool has_nonoccluded = false;  ///< the pair has a non-occluded mask; then:
  BadPixelStats nonoccluded;     ///< the same figures over its non-occluded pixels
  double ms = 0;                 ///< the matcher's wall time on this pair
  int num_disparities = 0;       ///< search range it was given
};
struct MiddleburyEvaluation {
  std::vector<MiddleburyPairResult> pairs;
  double mean_bad1 = 0, mean_bad2 = 0;  ///< percent, mean over the pairs
  double mean_invalid = 0;              ///< percent, mean over the pairs
  double mean_avg_error = 0;            ///< px, mean over the pairs
  int nonoccluded_pairs = 0;            ///< pairs with a non-occluded mask; the means below are over them
  BadPixelStats mean_nonoccluded;       ///< (pixels = their sum)
};

/// A matcher under test: the pair and the search range to use.
using MiddleburyMatcher = std::function<DisparityImage(const MiddleburyPair& pair, int num_disparities)>;

/// Runs `match` on every pair, timing it, and scores it with bad_pixels() (over all ground-truth
/// pixels, and over the non-occluded ones where the pair has a mask). Search range: the pair's
/// num_disparities when set, else its true range rounded up to a multiple of 16 (largest true
/// disparity + 1).
MiddleburyEvaluation evaluate_middlebury(const std::vector<MiddleburyPair>& pairs, const MiddleburyMatcher& match);

}  // namespace cropsight::stereo
