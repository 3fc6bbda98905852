#pragma once
// The broccoli pipeline from a PipelineSpec (pipeline_spec.hpp): `model` a shipped model's name or
// a model file (default kDefaultModel), `preset` and `sets` over the configuration the model
// records (config_for_model). `detector` and `threads` are unused: the broccoli pipeline
// runs single-threaded on the depth frame.
#include <memory>

#include "cropsight/pipeline/broccoli/pipeline.hpp"
#include "cropsight/pipeline/pipeline_spec.hpp"

namespace cropsight::pipeline::broccoli {

/// The model a broccoli pipeline runs when the spec names none: the one measured best on fields
/// it was not trained on (docs/pipelines/broccoli-heads.md).
inline constexpr const char* kDefaultModel = "broccoli-oes-general";

/// Throws Error naming the model file, the preset or the --set key.
std::unique_ptr<Pipeline> make_pipeline(const PipelineSpec& spec);

}  // namespace cropsight::pipeline::broccoli
