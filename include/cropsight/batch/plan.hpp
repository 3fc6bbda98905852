#pragma once
// The shard plan of a batch: what each array task (or local worker) processes, written once to
// DIR/plan.json so that every task reads the same plan whatever happens to the manifest later.
//
// A shard is one recording, or with shards.frames_per_shard = L a range of L frames of one.
// The seam rule: a shard OWNS frames [own_first, own_end) and PROCESSES
// [own_first − overlap, own_end + overlap) (clipped to the recording); it keeps the heads whose
// track began in its own range (TrackedHead::first_frame ∈ [own_first, own_end)). The frames
// before the range warm up the temporal filter's camera estimate; a head that enters the view in
// that leading overlap belongs to the previous shard, which follows it through its trailing
// overlap. Every head is therefore kept by exactly one shard as long as it stays in view for at
// most `overlap` frames (a broccoli head at 0.3 m/s and 7.5 fps crosses a 0.9 m view in ~22
// frames; the default overlap is 30). A head seen longer is cut like at a recording's end, and the
// merge (field_merge.hpp) fuses the two halves when they lie within its association radius.
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/batch/manifest.hpp"
#include "cropsight/pipeline/pipeline_spec.hpp"

namespace cropsight::batch {

struct Shard {
  std::string name;                    ///< folder under DIR/shards/: the recording's name [+ "-fFIRST"]
  std::string pass;                    ///< the recording's folder name: shards of one recording form one pass
  std::filesystem::path sequence;      ///< absolute
  int first_frame = 0, end_frame = 0;  ///< processed frames [first, end)
  int own_first = 0, own_end = 0;      ///< owned frames: heads whose track began here are kept
};

/// What the merge needs from the pipeline's config (so that it uses the tracker's own rule).
struct MergeRule {
  double association_radius_m = 0.05;  ///< tracking.association_radius_m of the batch's pipeline
  double market_min_mm = 100.0;        ///< sizing.market_min_mm: harvestable window
  double market_max_mm = 180.0;        ///< sizing.market_max_mm
};

struct BatchPlan {
  std::filesystem::path manifest;
  std::string crop;
  pipeline::PipelineSpec spec;
  MergeRule merge;
  SlurmOptions slurm;
  std::vector<Shard> shards;  ///< sorted by name; the index is the Slurm array task id
};

/// The shards of one recording of `frames` frames (the seam rule above), in frame order.
std::vector<Shard> plan_recording(const std::filesystem::path& sequence, int frames, const ShardingOptions& options);
/// Plans `manifest`: shards per the seam rule above, the merge rule from the pipeline's config.
BatchPlan plan_batch(const Manifest& manifest);
/// plan.json text (deterministic) and its reader (Error(path, ...) on anything malformed).
std::string plan_json(const BatchPlan& plan);
BatchPlan read_plan(const std::filesystem::path& path);

}  // namespace cropsight::batch
