#pragma once
// An optional step after the classification that changes the broccoli detector's candidates
// (steps/crease_split.hpp, steps/head_completion.hpp, steps/cnn_proposals.hpp): it may add,
// replace, grow or remove candidates of the frame state. The detector holds the refiners its
// config turns on and applies them in order, each with its own config slice and buffers.
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/pipeline/broccoli/steps/frame_state.hpp"

namespace cropsight::pipeline::broccoli::steps {

class Refiner {
 public:
  virtual ~Refiner() = default;
  /// Refines the candidates of `state` for `frame` (the frame the state was made from).
  virtual void refine(const RgbdFrame& frame, FrameState& state, StageTimer& timer) = 0;
};

}  // namespace cropsight::pipeline::broccoli::steps
