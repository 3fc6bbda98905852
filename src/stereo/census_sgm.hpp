#pragma once
// Internal (stereo module): our semi-global matcher on census costs, the engine behind
// compute_disparity() when DisparityConfig::engine == "census".
//
// Cost: census transform (Zabih & Woodfill 1994) over a census_width x census_height window
// (9 x 7 = 62 bits in one 64-bit word), Hamming distance between left(x) and right(x - d).
// Aggregation: SGM (Hirschmüller 2008) with 5 paths computed in one sweep over the rows (the two
// horizontal ones and the three that come from the previous row), 16-bit costs, 16 disparities
// per vector (GCC vector extensions: AVX2 when the CPU has it, chosen at run time, else SSE2).
// The image is split into a top band swept downwards and a bottom band swept upwards, one per
// thread, so both bands start at an image border (no warm-up seam in the middle).
// From the same summed cost row: left winner-take-all with OpenCV's uniqueness rule, the right
// view's winner (minimum along the diagonals x - d = const, no second matching run), left-right
// check, and the parabola sub-pixel fit.
#include <opencv2/core/mat.hpp>

#include "cropsight/stereo/disparity.hpp"

namespace cropsight::stereo::detail {

struct CensusSgmParams {
  int num_disparities = 128;  ///< multiple of 16
  int census_width = 9;       ///< odd; census_width * census_height - 1 <= 64
  int census_height = 7;      ///< odd
  int p1 = 10;                ///< Hamming-bit units; penalty of a +-1 disparity step
  int p2 = 120;               ///< Hamming-bit units; penalty of a larger step
  int p2_step = 0;            ///< grey levels; P2 / (1 + |dI| / p2_step) along the path (0 = constant P2)
  int cost_box = 1;           ///< columns; horizontal box sum of the costs before SGM (odd, 1 = none)
  int uniqueness_ratio = 10;  ///< percent (OpenCV's rule); 0 = off
  int lr_check = 1;           ///< px; -1 = off
  bool allow_avx2 = true;     ///< false forces the portable SSE2 kernel (tests compare both)
  int bands = 2;              ///< 1 or 2 independent sweeps (top-down / bottom-up), one per thread
};

/// Left-reference disparity of a rectified pair of equal-size CV_8UC1 images. Pixels without a
/// consistent, unique match (or matched outside the right image) are NaN. Disparities are in
/// [0, num_disparities - 1] pixels with sub-pixel fraction.
DisparityImage census_sgm(const cv::Mat& left, const cv::Mat& right, const CensusSgmParams& p);

}  // namespace cropsight::stereo::detail
