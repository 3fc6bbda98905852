#pragma once
// The paper's FEC baseline as a PCL user would write it, for timing comparisons (cropsight bench
// broccoli) and cross-checks: pcl::IntegralImageNormalEstimation (covariance method) →
// [pcl::StatisticalOutlierRemoval] → pcl::EuclideanClusterExtraction (k-d tree) →
// pcl::VFHEstimation per cluster → the same classifier (learning::Model) as our detectors.
// PCL types stay inside the .cpp (pimpl): this header does not include PCL.
#include <memory>
#include <vector>

#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/detector_config.hpp"

namespace cropsight::pipeline::broccoli {

class PclReferencePipeline {
 public:
  /// Uses cfg.depth, cfg.normals, cfg.outliers (when enabled) and cfg.fec. The model's features
  /// must be exactly {"vfh"} (PCL computes VFH only); throws Error(where, ...) otherwise.
  PclReferencePipeline(const DetectorConfig& cfg, std::shared_ptr<const learning::Model> model,
                       const std::string& where = "model");
  ~PclReferencePipeline();
  PclReferencePipeline(const PclReferencePipeline&) = delete;
  PclReferencePipeline& operator=(const PclReferencePipeline&) = delete;

  /// Runs every stage on `frame` (stages timed as "cloud", "normals", "outliers", "clustering",
  /// "features", "classify"). Returns the number of clusters.
  std::size_t process(const RgbdFrame& frame);
  /// Pixel indices of each cluster of the last frame (ascending) and their scores.
  const std::vector<std::vector<int>>& clusters() const;
  const std::vector<float>& scores() const;
  StageTimer& timer();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cropsight::pipeline::broccoli
