#pragma once
// The batch manifest: which recordings to process, with which pipeline, how to cut them into
// shards and how to ask Slurm for resources (docs/batch.md has the full format):
//
//   recordings:                    # sequence folders, relative to this file or absolute
//     - passes/row-01
//     - passes/row-02
//   pipeline:
//     crop: broccoli               # the crop whose make_pipeline builds every shard's pipeline
//     model: broccoli-oes-general  # a shipped model's name or a file (optional)
//     config: broccoli-uk          # a preset name or a YAML file (optional)
//     sets: {tracking.use_poses: true}   # --set pairs (optional)
//   shards:                        # optional
//     frames_per_shard: 0          # 0 = one shard per recording; else frame ranges of this length
//     overlap_frames: 30           # frames processed before a range to warm up the filter (plan.hpp)
//   slurm:                         # optional; options of `batch --engine slurm` override them
//     partition: ""  account: ""  time: "01:00:00"  mem: "2G"  cpus_per_task: 1
//     max_retries: 2               # resubmissions of a failed array task
//     max_parallel: 0              # array throttle (%N); 0 = none
//
// read_manifest checks everything a batch needs before any work is submitted: the YAML's keys,
// each recording's layout (io::SequenceReader), that no two recordings would write the same shard
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

/// Reads and checks a manifest (see the top of this file). Throws Error(file or recording, ...).
Manifest read_manifest(const std::filesystem::path& file);

/// The crops a batch can run (broccoli; the others' outputs are not merged yet).
bool batch_supports_crop(const std::string& crop);

}  // namespace cropsight::batch
