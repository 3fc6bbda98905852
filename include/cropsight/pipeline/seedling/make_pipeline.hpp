#pragma once
// The seedling pipeline from a PipelineSpec (pipeline_spec.hpp): `preset` (default kDefaultPreset)
// and `sets`. The seedling pipeline loads no model; `model`, `detector` and `threads` are unused.
#include <memory>

#include "cropsight/pipeline/pipeline_spec.hpp"
#include "cropsight/pipeline/seedling/pipeline.hpp"

namespace cropsight::pipeline::seedling {

/// The preset a seedling pipeline runs when the spec names none (configs/seedling.yaml).
inline constexpr const char* kDefaultPreset = "seedling";

/// Throws Error naming the preset file or the --set key.
std::unique_ptr<Pipeline> make_pipeline(const PipelineSpec& spec);

}  // namespace cropsight::pipeline::seedling
