#pragma once
// What the broccoli detector's steps hand on to each other within one frame (steps/*.hpp; the
// order is Detector::process): the cloud, what the cloud step learnt of the frame's depth, the
// clustering's owner image and the candidate pool. Every buffer in it is reused from frame to
// frame. Frames: the cloud is in metres in the camera frame (x right, y down, z forward), one
// point per depth pixel; pixel indices are v * width + u.
#include <limits>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/pipeline/broccoli/candidate.hpp"
#include "cropsight/segmentation/organized_clustering.hpp"

namespace cropsight::pipeline::broccoli::steps {

/// One frame's depth as the cloud step found it: the range-aware thresholds and the noise.
struct FrameConditions {
  float soil_depth = std::numeric_limits<float>::quiet_NaN();   ///< m, camera z; NaN unless range.* needs it
  float noise_sigma = std::numeric_limits<float>::quiet_NaN();  ///< m; NaN unless denoise.above > 0
  bool denoised = false;                                        ///< the depth was bilateral-filtered
  /// The frame's OES thresholds: oes.*, scaled to the soil's range when range.reference_range > 0
  /// (the clustering and the crease split read them).
  segmentation::OesConfig oes;
};

struct FrameState {
  /// Depth-window filtered (NaN outside it); normals where the normals step computed them;
  /// ground-truth labels when the frame has them.
  OrganizedCloud cloud;
  FrameConditions conditions;
  /// Per pixel: the index of the candidate holding it, or -1; the organised clusterings' label
  /// image (OES, ORG), empty after FEC. The crease split and the head completion keep it up to
  /// date; the CNN proposals, the last refiner, do not (nothing reads it after them).
  std::vector<int> owners;
  CandidatePool candidates;
};

}  // namespace cropsight::pipeline::broccoli::steps
