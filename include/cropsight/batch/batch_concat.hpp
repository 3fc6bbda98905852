#pragma once
// The last step of a potato, grape or seedling batch: their results are per frame, not a map, so
// they are concatenated rather than merged. The done shards' rows (crop_shards.hpp), in plan
// order, go into one file DIR/targets.csv, DIR/bunches.csv or DIR/seedlings.csv with the recording
// and the shard in front of every row, and DIR/passes.csv sums them per recording: shards,
// frames processed (overlaps included), detections, items (potato targets, grape bunches, seedlings found) and CPU
// seconds. Each file is written atomically; equal shards give equal bytes whichever engine ran them.
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/batch/plan.hpp"
#include "cropsight/batch/shard_runner.hpp"

namespace cropsight::batch {

struct RecordingSummary {
  std::string pass;
  int shards = 0, frames = 0;
  long detections = 0, items = 0;
  double cpu_s = 0.0;
};

struct ConcatSummary {
  std::string file;  ///< the concatenated file's name in DIR
  std::size_t rows = 0;
  std::vector<ShardRecord> records;          ///< plan order
  std::vector<RecordingSummary> recordings;  ///< sorted by name
};

/// Concatenates the shards of `plan` in `batch_dir` (all must be done) into the files above.
/// Throws Error naming a shard that is not done or a shard file whose header differs.
ConcatSummary concat_batch(const BatchPlan& plan, const std::filesystem::path& batch_dir);

}  // namespace cropsight::batch
