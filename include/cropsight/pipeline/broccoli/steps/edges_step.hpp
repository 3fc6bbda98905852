#pragma once
// Organised edges of the broccoli detector's cloud, for OES only (StageTimer "edges";
// geometry/organized_edges.hpp for the labels): one byte of geometry::EdgeLabel bits per pixel,
// the barriers the OES flood fill stops at. The label buffer is reused from frame to frame.
#include <cstdint>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/geometry/organized_edges.hpp"

namespace cropsight::pipeline::broccoli::steps {

class EdgesStep {
 public:
  /// `enabled`: the clustering reads edges (OES); otherwise run() does nothing.
  EdgesStep(geometry::OrganizedEdgeConfig cfg, bool enabled) : cfg_(cfg), enabled_(enabled) {}

  /// The edge labels of `cloud` (one per pixel; empty when disabled), valid until the next call.
  const std::vector<std::uint8_t>& run(const OrganizedCloud& cloud, StageTimer& timer) {
    if (enabled_) {
      auto t = timer.scope("edges");
      geometry::detect_organized_edges(cloud, cfg_, edges_);
    }
    return edges_;
  }

 private:
  geometry::OrganizedEdgeConfig cfg_;
  bool enabled_;
  std::vector<std::uint8_t> edges_;
};

}  // namespace cropsight::pipeline::broccoli::steps
