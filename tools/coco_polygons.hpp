#pragma once
// COCO polygon segmentation of a binary mask, shared by the tools that write COCO sets
// (potato_paste, broccoli_depth_coco): the outer contours of `mask` (non-zero = inside),
// simplified to 1 pixel (Douglas-Peucker), each as a flat [x0, y0, x1, y1, ...] list; contours
// of fewer than 3 points or under 4 pixels² are left out.
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace cropsight::tools {

inline nlohmann::json coco_polygons(const cv::Mat& mask) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  nlohmann::json out = nlohmann::json::array();
  for (const auto& c : contours) {
    if (c.size() < 3 || cv::contourArea(c) < 4) continue;
    std::vector<cv::Point> p;
    cv::approxPolyDP(c, p, 1.0, true);
    if (p.size() < 3) continue;
    nlohmann::json flat = nlohmann::json::array();
    for (const auto& q : p) flat.push_back(q.x), flat.push_back(q.y);
    out.push_back(flat);
  }
  return out;
}

}  // namespace cropsight::tools
