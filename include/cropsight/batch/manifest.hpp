#pragma once
// The batch manifest: which recordings to process, with which pipeline, how to cut them into
// shards and how to ask Slurm for resources (docs/batch.md has the full format):
//
//   recordings:                    # folders, relative to this file or absolute: RGB-D sequences
//                                  # (seedling: stereo data sets; crop_shards.hpp)
//     - passes/row-01
//     - passes/row-02
//   pipeline:
//     crop: broccoli               # broccoli, potato, grape or seedling: its make_pipeline builds
//                                  # every shard's pipeline
//     model: broccoli-oes-general  # a shipped model's name or a file (optional)
//     config: broccoli-uk          # a preset name or a YAML file (optional)
//     sets: {tracking.use_poses: true}   # --set pairs (optional)
//     detector: detector-grape     # a 2D detector (grape; optional: else each recording's detections.json)
//   shards:                        # optional
//     frames_per_shard: 0          # 0 = one shard per recording; else frame ranges of this length
//     overlap_frames: 30           # frames processed before a range to warm up the filter (plan.hpp)
//   slurm:                         # optional; options of `batch --engine slurm` override them
//     partition: ""  account: ""  time: "01:00:00"  mem: "2G"  cpus_per_task: 1
//     max_retries: 2               # resubmissions of a failed array task
//     max_parallel: 0              # array throttle (%N); 0 = none
//
// read_manifest checks everything a batch needs before any work is submitted: the YAML's keys,
// each recording's layout (crop_shards.hpp), that no two recordings would write the same shard
// folder, and the pipeline spec (the crop's make_pipeline is run once: unknown presets, models
// and --set keys fail here). Every problem is an Error naming the manifest (or the recording).
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/pipeline/pipeline_spec.hpp"

namespace cropsight::batch {

struct ShardingOptions {
  int frames_per_shard = 0;  ///< frames; 0 = one shard per recording
  int overlap_frames = 30;   ///< frames processed before a range and after it (plan.hpp: the seam rule)
};

struct SlurmOptions {
  std::string partition;          ///< "" = the cluster's default
  std::string account;            ///< "" = the user's default
  std::string time = "01:00:00";  ///< per array task, Slurm's time format
  std::string mem = "2G";         ///< per array task, Slurm's memory format
  int cpus_per_task = 1;
  int max_retries = 2;   ///< resubmissions of an array task whose shard is not done
  int max_parallel = 0;  ///< array throttle (%N); 0 = none
};

struct Manifest {
  std::filesystem::path file;                     ///< the manifest itself
  std::vector<std::filesystem::path> recordings;  ///< absolute
  std::string crop = "broccoli";
  pipeline::PipelineSpec spec;  ///< preset / model resolved to absolute paths when they are files
  ShardingOptions sharding;
  SlurmOptions slurm;
};

/// Reads and checks a manifest (see the top of this file; a *.csv file: read_manifest_csv).
/// Throws Error(file or recording, ...).
Manifest read_manifest(const std::filesystem::path& file);

/// The CSV form, one row a recording, for scripts and spreadsheets:
///
///   recording,crop,model,sets
///   passes/row-01,broccoli,broccoli-oes-general,tracking.use_poses=true
///   passes/row-02,,,
///
/// Columns: recording (required; relative to the file or absolute), crop, model, config,
/// detector, sets (space-separated key=value), frames_per_shard, overlap_frames. A batch runs one
/// pipeline, so every column but recording holds one value: an empty cell takes it from the other
/// rows, a different one is an error naming both lines. A field may be double-quoted; lines
/// starting with # are comments. Slurm options come from `batch`'s command line.
Manifest read_manifest_csv(const std::filesystem::path& file);

}  // namespace cropsight::batch
