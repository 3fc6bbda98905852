#pragma once
// Refiner (cnn.model set; StageTimer "cnn"): heads the depth CNN finds where the clustering
// accepted none. The frame's depth is encoded for the network (depth_encoding.hpp) and run once;
// its boxes (score >= cnn.min_score, best first) and its head mask are decoded in image pixels
// (nn/center_decode.hpp). A box's mask pixels that hold a point of the cloud become a proposal
// (at least cnn.min_points of them), dropped when its point-set IoU with an accepted head (or an
// earlier proposal) exceeds cnn.max_overlap. A proposal takes its pixels from the rejected
// candidates it overlaps (every pixel stays in one candidate; one taken whole is removed) and is
// appended as a head scoring just above the head threshold, ordered among proposals by the CNN's
// score, so that it ranks after every classified head. About 55 ms per 512 x 424 frame on one
// core (docs/pipelines/broccoli-heads.md).
#include <memory>
#include <vector>

#include "cropsight/pipeline/broccoli/detector_config.hpp"
#include "cropsight/pipeline/broccoli/steps/classification_step.hpp"
#include "cropsight/pipeline/broccoli/steps/refiner.hpp"

namespace cropsight::nn {
class CenterNetOnnx;
}

namespace cropsight::pipeline::broccoli::steps {

class CnnProposals final : public Refiner {
 public:
  /// Loads cnn.model; throws Error(cnn.model, ...) unless it is an .onnx detector of the one class
  /// "head". `classification` (the detector's, which must outlive this step) gives the threshold.
  CnnProposals(CnnConfig cfg, const ClassificationStep& classification);
  ~CnnProposals() override;

  void refine(const RgbdFrame& frame, FrameState& state, StageTimer& timer) override;

 private:
  // Moves the proposal's pixels out of the rejected candidates that hold them.
  void take_pixels(const std::vector<int>& pixels, FrameState& state);

  CnnConfig cfg_;
  const ClassificationStep& classification_;
  std::unique_ptr<nn::CenterNetOnnx> cnn_;
  std::vector<int> rest_;  // a rejected candidate less the proposal's pixels
};

}  // namespace cropsight::pipeline::broccoli::steps
