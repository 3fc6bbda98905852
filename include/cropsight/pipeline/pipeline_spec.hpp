#pragma once
// One way to build a pipeline: every front-end (the CLI, the ROS bridge, the benchmarks, the
// tools, the examples, and the Python package, the studio and the batch runner to come) says what
// it wants as a PipelineSpec and calls its crop's make_pipeline (pipeline/<crop>/make_pipeline.hpp):
//
//   auto pipe = pipeline::broccoli::make_pipeline({.sets = {"track=false"}, .model = "broccoli-oes-uk"});
//
// The spec names presets and models the way the CLI's --config and --model do: a name resolved in
// the data folder (io::find_preset, io::find_model: configs/NAME.yaml, models/NAME.*) or a file.
// None of the front-ends assembles a crop's config or models itself.
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"

namespace cropsight::pipeline {

struct PipelineSpec {
  /// The preset (a name or a YAML file); "" = the crop's default preset (its make_pipeline says which).
  std::string preset;
  /// Overrides of the preset's keys, "key=value" each (the CLI's --set); applied in order.
  std::vector<std::string> sets;
  /// The crop's main model (a shipped model's name or a file); "" = the crop's default.
  std::string model;
  /// A 2D detector model where the crop runs one (grape: boxes; potato: an ONNX detector); "" = none
  /// (grape: boxes come with each frame) or the preset's (potato).
  std::string detector;
  /// Worker threads where a step runs several (grape segmenter and detector); 0 = the preset's.
  int threads = 0;
};

/// The values of `spec`'s preset (or of `default_preset` when it names none; no preset when both
/// are empty) overlaid with its sets. Throws Error naming the preset file, or "--set" with the key.
ConfigMap spec_values(const PipelineSpec& spec, const std::string& default_preset);

/// Where a spec's values come from, for error lines: "configs/potato.yaml / --set".
std::string spec_where(const PipelineSpec& spec, const std::string& default_preset);

}  // namespace cropsight::pipeline
