#pragma once
// The grape pipeline from a PipelineSpec (pipeline_spec.hpp):
//   preset    the pipeline preset (ROI, cut point; default kDefaultPreset)
//   model     the segmenter: a model file (.pt network, .json GBDT), a shipped model's name
//             (models/; looked up before presets, whose training recipes share those names) or a
//             segmenter preset (e.g. grape-best); default kDefaultSegmenter
//   sets      keys of the pipeline preset, "segmenter.KEY=V" among them for the segmenter's keys
//             (segmenter.votes, segmenter.ensemble, ...)
//   detector  the 2D detector (a shipped model's name, e.g. detector-grape, whose runtime the key
//             detector.backend picks: nn::open_center_detector; or a .onnx / .pt file); "" = none,
//             every frame then comes with its boxes
//   threads   the segmenter's and the detector's threads; 0 = the segmenter preset's
#include <memory>

#include "cropsight/pipeline/grape/pipeline.hpp"
#include "cropsight/pipeline/grape/segmenter.hpp"
#include "cropsight/pipeline/pipeline_spec.hpp"

namespace cropsight::pipeline::grape {

/// The pipeline preset when the spec names none (configs/grape-camera.yaml).
inline constexpr const char* kDefaultPreset = "grape-camera";
/// The segmenter when the spec names none: the shipped ensemble (configs/grape-best.yaml).
inline constexpr const char* kDefaultSegmenter = "grape-best";

/// The segmenter's configuration from `spec` (model and the segmenter.* sets; threads).
SegmenterConfig segmenter_config(const PipelineSpec& spec);

/// Throws Error naming the preset, the --set key or the model file.
std::unique_ptr<Pipeline> make_pipeline(const PipelineSpec& spec);

}  // namespace cropsight::pipeline::grape
