#pragma once
// What the grape pipeline returns for one frame (Pipeline::process, pipeline.hpp). Plain data in
// C++17 (Eigen and the standard library only), so that the ROS node, built as C++17, uses it as it
// is. Pixels: x = column, y = row, origin top-left. Points: camera frame (x right, y down,
// z forward), metres.
#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <optional>
#include <vector>

#include "cropsight/core/cloud.hpp"
#include "cropsight/core/geometry_types.hpp"
#include "cropsight/core/timer.hpp"

namespace cropsight::pipeline::grape {

/// One 2D detection: the detector's, or read from a COCO-style file (read_coco_detections).
struct Detection {
  Box2D box;
  int category = 0;  ///< 1 = grape bunch, 2 = peduncle (the dataset's COCO categories)
  float score = 1.f;
  long annotation = -1;  ///< index in the file's array (read_coco_detections), for messages
};

/// A cut point on a bunch's peduncle, camera frame.
struct CutPoint {
  Eigen::Vector3f position = Eigen::Vector3f::Zero();    ///< m: centroid of the peduncle cluster
  Eigen::Vector3f direction = Eigen::Vector3f::UnitY();  ///< unit principal axis, pointing up in
                                                         ///< the image (y <= 0)
  int confidence = 0;  ///< points of the peduncle cluster: the more, the better supported
};

/// One bunch's result.
struct Bunch {
  Box2D roi;                          ///< pixels (Eq. 1, merged, clipped to the image)
  Cloud cloud;                        ///< m, camera frame; colours (0..1), normals, segmenter labels
  std::optional<CutPoint> cut_point;  ///< none: no peduncle cluster of min_points points
};

/// One frame's result.
struct FrameResult {
  std::vector<Detection> detections;  ///< the boxes used (detector's, or as given)
  std::vector<Detection> outside;     ///< bunch / peduncle boxes wholly outside the image
  std::vector<Bunch> bunches;         ///< one per ROI with at least 3 points, in ROI order
  StageTimer timer;  ///< this frame's wall-clock stages: detect (with a detector), roi, segment, cut_point
  /// Bunches with a cut point.
  std::size_t cut_points() const {
    return std::size_t(std::count_if(bunches.begin(), bunches.end(), [](const Bunch& b) { return bool(b.cut_point); }));
  }
};

}  // namespace cropsight::pipeline::grape
