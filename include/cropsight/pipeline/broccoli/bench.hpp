#pragma once
// What `cropsight bench broccoli` measures, for library users who compare the clustering variants
// on their own frames: the OES, ORG and FEC detectors and the PCL reference pipeline
// (pcl_reference.hpp) timed on the same frames in the same process (timing.hpp), each with the
// settings it ran with, and optionally sizing + the temporal filter on the OES detections.
//
// Settings: the model's own pipeline runs with what the model records (as `detect` and `eval
// broccoli --model` run it); the others with their presets configs/broccoli-<pipeline>-<variety>.yaml
// and VFH features, the only feature PCL computes. `preset` and `sets` lie over every one of them.
// Every pipeline scores its clusters with the model's classifier (model_for_variant: for timing
// only). Statistical outlier removal is off in every pipeline unless `sor`, so that FEC and the PCL
// reference do the paper's reference work (normals + Euclidean clustering + VFH + SVM).
//
// Call from a single-threaded section, as timing.hpp says.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/pipeline/broccoli/config.hpp"
#include "cropsight/pipeline/broccoli/detector_config.hpp"
#include "cropsight/pipeline/pipeline_timing.hpp"
#include "cropsight/tracking/head_mapper.hpp"

namespace cropsight::pipeline::broccoli {

/// What to time, named as a PipelineSpec names a pipeline (its errors name the CLI's options).
struct BenchSpec {
  /// A shipped model's name or a model file. Its classifier scores every pipeline's clusters, so
  /// it must use VFH features alone when another pipeline than its own runs.
  std::string model;
  std::string variety = "uk";     ///< the other pipelines' presets: broccoli-<pipeline>-<variety> (uk | spain)
  std::string preset;             ///< a preset laid over every pipeline's settings ("" = none), then `sets`
  std::vector<std::string> sets;  ///< "key=value" each (the CLI's --set)
  bool sor = false;               ///< statistical outlier removal on (else off in every pipeline)
  std::vector<std::string> pipelines = {"oes", "org", "fec", "pcl"};  ///< which to time
  bool track = false;  ///< also time sizing + the temporal filter on the OES detections (needs "oes")
  int repeat = 1;      ///< passes over the frames

  /// Throws Error("--repeat" | "--variety" | "--pipelines" | "--track", ...) for a value out of
  /// range, an unknown pipeline or tracking without OES.
  void validate() const;
};

/// One timed pipeline and the settings it ran with.
struct BenchedPipeline {
  std::string settings;  ///< "model" (what the model records) or "preset broccoli-<pipeline>-<variety>"
  /// The detector settings it ran with (the PCL reference reads depth, normals, outliers and fec).
  DetectorConfig detector;
  PipelineTiming timing;
  std::optional<SpeedRatio> vs_pcl;  ///< the PCL reference's time over this one's, when the reference ran
};

/// Sizing + the temporal filter on the OES detections (time_tracking).
struct BenchedTracking {
  tracking::HeadMapperConfig mapping;  ///< the OES pipeline's sizing.* and tracking.* keys
  PipelineTiming timing;
  SpeedRatio vs_oes;  ///< this time over the OES detector's
};

struct BenchResult {
  std::map<std::string, BenchedPipeline> detectors;  ///< by name ("oes", "org", "fec"): those asked for
  std::optional<BenchedPipeline> pcl_reference;      ///< settings: the FEC preset's
  std::optional<BenchedTracking> tracking;           ///< with BenchSpec::track
};

/// The settings `bench` times `variant` with when it is not the model's own pipeline: the
/// variety's preset (configs/broccoli-<variant>-<variety>.yaml), then spec.preset and spec.sets,
/// VFH features, outlier removal as spec.sor. Throws Error naming the preset or the --set key.
Config variant_config(const BenchSpec& spec, Variant variant);

/// Times what `spec` asks for on `frames` (in memory, without label images). Throws Error naming
/// the model file, the preset or the --set key, or the option validate() names; Error("bench", ...)
/// when `frames` is empty.
BenchResult bench(const BenchSpec& spec, const std::vector<RgbdFrame>& frames);

}  // namespace cropsight::pipeline::broccoli
