#pragma once
// The potato pipeline from a PipelineSpec (pipeline_spec.hpp): `preset` (default kDefaultPreset)
// and `sets`; `model` an ONNX detector (a shipped model's name or a file) run in place of the
// preset's detector (detector.backend=onnx). `detector` and `threads` are unused.
#include <memory>

#include "cropsight/pipeline/pipeline_spec.hpp"
#include "cropsight/pipeline/potato/pipeline.hpp"

namespace cropsight::pipeline::potato {

/// The preset a potato pipeline runs when the spec names none (configs/potato.yaml: the classical
/// detector, measured best on the orientation shots; docs/pipelines/potatoes.md).
inline constexpr const char* kDefaultPreset = "potato";

/// The configuration make_pipeline builds from `spec` (for callers that need only a step of it).
Config spec_config(const PipelineSpec& spec);

/// Throws Error naming the preset file, the --set key or the model file.
std::unique_ptr<Pipeline> make_pipeline(const PipelineSpec& spec);

}  // namespace cropsight::pipeline::potato
