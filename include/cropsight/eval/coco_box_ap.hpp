#pragma once
// COCO box average precision for one class, as pycocotools' COCOeval computes it (bbox, one
// area range "all", maxDets 100, no crowd regions).
//
// Boxes are image pixels with continuous corners (core/detection2d.hpp): area = w * h, IoU of
// continuous rectangles (COCO's bbox IoU).
//
// Matching, image by image (COCOeval.evaluateImg): detections in decreasing score (at most
// max_detections per image); each takes the not-yet-matched truth of the highest IoU among those
// with IoU >= t and is then a true positive, otherwise a false positive. This differs from
// eval/voc_ap.hpp (pascalvoc.py: the best truth over all, taken or not; inclusive pixel areas).
//
// AP (COCOeval.accumulate): all images' detections ranked by decreasing score (stable), precision
// made non-increasing from the right, then sampled at the 101 recall points 0, 0.01, ..., 1 (the
// first rank whose recall reaches each point; 0 past the last recall) and averaged: COCO's
// 101-point interpolation, not the all-point area of voc_ap.hpp / detection_ap.hpp. AP50:95 is the
// mean over t = 0.50, 0.55, ..., 0.95. NaN when the class has no truth (COCO writes -1).
#include <cstdint>
#include <vector>

#include "cropsight/core/detection2d.hpp"

namespace cropsight::eval {

/// One image's truths and scored detections of the class being evaluated.
struct CocoApImage {
  std::vector<Detection2D> truth;
  std::vector<Detection2D> detections;
};

/// 101-point interpolated AP at IoU threshold t.
double coco_box_ap(const std::vector<CocoApImage>& images, double iou_threshold, int max_detections = 100);

struct CocoApSummary {
  double ap50 = 0, ap75 = 0;
  double ap50_95 = 0;  ///< mean AP over 0.50:0.05:0.95
  std::int64_t images = 0, truths = 0, detections = 0;
};
CocoApSummary coco_box_ap_summary(const std::vector<CocoApImage>& images, int max_detections = 100);

}  // namespace cropsight::eval
