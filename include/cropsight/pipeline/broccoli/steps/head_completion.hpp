#pragma once
// Refiner (detection.grow_tolerance > 0; StageTimer "completion"): a rough or noisy head that the
// clustering broke into one kept piece and debris gets its whole mask back. Every head grows over
// the valid pixels no candidate holds, joining 4-neighbours closer than grow_tolerance (m) within
// grow_radius (m) of its centroid; the most confident head claims contested pixels first
// (segmentation/segment_growth.hpp). Only the masks, boxes and centroids change, not the scores.
// The owner image is the organised clusterings' (FrameState::owners, grown pixels written into
// it); after FEC, which has none, the step builds one. Buffers are reused from frame to frame.
#include <vector>

#include "cropsight/pipeline/broccoli/steps/refiner.hpp"
#include "cropsight/segmentation/segment_growth.hpp"

namespace cropsight::pipeline::broccoli::steps {

class HeadCompletion final : public Refiner {
 public:
  /// tolerance and radius in metres.
  explicit HeadCompletion(segmentation::SegmentGrowthOptions options) : options_(options) {}

  void refine(const RgbdFrame& frame, FrameState& state, StageTimer& timer) override;

 private:
  segmentation::SegmentGrowthOptions options_;
  std::vector<Segment*> segments_;  // every candidate's segment, in order
  std::vector<int> grow_order_;     // the heads, best score first
  segmentation::SegmentGrowthWorkspace growth_;
};

}  // namespace cropsight::pipeline::broccoli::steps
