#pragma once
// Timing of the potato loop as deployed, for `cropsight bench potato` ("per-stage
// milliseconds at 640x480, single-threaded"; target >= 30 fps, the D415's rate): frames already in
// memory (I/O excluded) without label images, one warm-up frame, then `repeat` passes, each a fresh
// approach (reset(): selection starts again), wall clock and thread CPU time per frame, and the
// stages of Pipeline::process (detect, locate, track, orient). OpenCV runs on one thread
// while timing; call from a single-threaded section (cap TBB). A baseline timed in the same process (an RGB -> Lab
// conversion of each frame, the first operation of the classical detector) turns the figures into ratios that hold on a
// noisy machine.
#include <vector>

#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/pipeline/pipeline_timing.hpp"
#include "cropsight/pipeline/potato/pipeline.hpp"

namespace cropsight::pipeline::potato {

/// `repeat` passes of pipeline.process over `frames` (reset() before each); `clusters` counts the
/// frames with a target. Throws Error when `frames` is empty or repeat < 1.
PipelineTiming time_potato_pipeline(Pipeline& pipeline, const std::vector<RgbdFrame>& frames, int repeat);

/// The baseline: cv::cvtColor RGB -> Lab of each frame's colour image, `repeat` passes.
PipelineTiming time_lab_conversion(const std::vector<RgbdFrame>& frames, int repeat);

}  // namespace cropsight::pipeline::potato
