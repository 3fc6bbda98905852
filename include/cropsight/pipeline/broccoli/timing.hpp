#pragma once
// Timing of the broccoli pipelines as deployed, for `cropsight bench broccoli` and library users
// who compare settings on their own frames: frames already in memory (I/O excluded) and without
// label images, one warm-up frame first, wall clock and this thread's CPU time per frame. Call
// from a single-threaded section (the paper's figures are single-threaded; the CLI caps TBB to
// one thread) so that the CPU time is the pipeline's alone. Speed ratios between pipelines timed
// in the same process are the robust figures on a shared machine.
#include <memory>
#include <string>
#include <vector>

#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/detector.hpp"
#include "cropsight/pipeline/broccoli/pcl_reference.hpp"
#include "cropsight/pipeline/pipeline_timing.hpp"
#include "cropsight/tracking/head_mapper.hpp"

namespace cropsight::pipeline::broccoli {

/// `repeat` passes of detector.process over `frames`, after one warm-up frame. Throws Error when
/// `frames` is empty.
PipelineTiming time_detector(Detector& detector, const std::vector<RgbdFrame>& frames, int repeat);
/// The same for the PCL reference pipeline.
PipelineTiming time_pcl_reference(PclReferencePipeline& pcl, const std::vector<RgbdFrame>& frames, int repeat);
/// Sizing + the temporal filter on `detector`'s detections of the same frames: per frame
/// HeadMapper::add_frame + predict_missed, finish() once per pass — everything tracking adds to
/// the detector (Pipeline steps 2-4). The detector runs untimed in that loop.
PipelineTiming time_tracking(Detector& detector, const tracking::HeadMapperConfig& cfg,
                             const std::vector<RgbdFrame>& frames, int repeat);

/// `model`'s classifier under the tag of another clustering variant (rebuilt from its own
/// serialisation), so that one model times every variant: for timing only.
std::shared_ptr<const learning::Model> model_for_variant(const std::shared_ptr<const learning::Model>& model,
                                                         Variant variant, const std::string& where);

}  // namespace cropsight::pipeline::broccoli
