#pragma once
// One shard of a batch, run: the crop's make_pipeline over the shard's frames, what it kept
// (plan.hpp's seam rule) written to DIR/shards/NAME/ as
//
//   field-map.csv   broccoli: the shard's heads (tracking/field_map_io.hpp), field frame of its recording
//                   (potato targets.csv, grape bunches.csv, seedling seedlings.csv: crop_shards.hpp)
//   shard.json      what ran: frames, detections, items, wall and CPU seconds, host — the done marker
//
// The folder is written under a temporary name and renamed whole when complete (io::TempDirectory),
// with shard.json written last inside it, so a shard folder exists only when it is done: a task
// killed or failed at any moment leaves at most a hidden temporary, which the next attempt removes
// (io::remove_stale_temporaries: a temporary whose process is gone on this machine).
#include <cstddef>
#include <filesystem>
#include <string>

#include "cropsight/batch/plan.hpp"

namespace cropsight::batch {

/// shard.json: what a finished shard reports.
struct ShardRecord {
  std::string name, pass;
  int frames = 0;       ///< frames processed (overlaps included)
  long detections = 0;  ///< detections over those frames
  int items = 0;        ///< kept (seam rule): broccoli heads, potato targets, grape bunches, seedlings
  double wall_s = 0.0;  ///< seconds from the pipeline's construction to the folder's rename
  double cpu_s = 0.0;   ///< CPU seconds of the thread that ran the shard
  std::string host;     ///< the machine that ran it
};

std::filesystem::path shard_folder(const std::filesystem::path& batch_dir, const Shard& shard);
/// Whether the shard's folder is complete (its shard.json exists).
bool shard_done(const std::filesystem::path& batch_dir, const Shard& shard);
/// Runs shard `index` of `plan` into `batch_dir`; throws Error naming the recording's file or the
/// model when a frame cannot be read or the pipeline cannot be built (nothing is left that looks done).
ShardRecord run_shard(const BatchPlan& plan, std::size_t index, const std::filesystem::path& batch_dir);
/// Reads a shard.json; throws Error(path, ...).
ShardRecord read_shard_record(const std::filesystem::path& path);

}  // namespace cropsight::batch
