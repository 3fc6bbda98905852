#pragma once
// Internal: the segmentation steps of measure/orientation on cv::Mat (OpenCV stays out of the
// public header). Every function takes the cropped region as CV_8UC3 in r, g, b order and
// returns a CV_8UC1 mask, 255 = potato.
#include <opencv2/core.hpp>

#include "cropsight/measure/orientation.hpp"

namespace cropsight::measure::detail {

cv::Mat segment_canny(const cv::Mat& rgb, const OrientationConfig& cfg);
cv::Mat segment_kmeans(const cv::Mat& rgb, const OrientationConfig& cfg);
cv::Mat segment_ours(const cv::Mat& rgb, const OrientationConfig& cfg);

/// 255 on the outer `width` pixels of a rows x cols region, 0 inside.
cv::Mat border_mask(int rows, int cols, int width);
/// The 8-connected component of `mask` whose pixels come nearest the region's centre (ties: the
/// larger), with its holes filled; empty mask when there is none.
cv::Mat component_nearest_centre(const cv::Mat& mask);

}  // namespace cropsight::measure::detail
