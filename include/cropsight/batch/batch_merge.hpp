#pragma once
// A batch's last step: the done shards' field maps, in plan order, brought into one field frame
// and merged (field_merge.hpp), then DIR/field-map.csv, passes.csv, rows.csv and, when the
// recordings carry geo_origin.yaml, DIR/field-map.geojson (field_outputs.hpp), each written
// atomically.
//
// The common field frame: without geo origins, every recording's poses are taken to share one
// field frame (the simulator's passes over one field do). With them, the first recording's origin
// (in plan order) defines it, and each recording's heads go through WGS84 into it
// (io::GeoReference), so passes recorded with different origins or headings line up. A mix of
// recordings with and without an origin is refused (check_geo_origins, before any work).
#include <filesystem>
#include <optional>
#include <vector>

#include "cropsight/batch/field_merge.hpp"
#include "cropsight/batch/plan.hpp"
#include "cropsight/batch/shard_runner.hpp"
#include "cropsight/io/geo_origin.hpp"

namespace cropsight::batch {

struct MergeSummary {
  std::size_t maps = 0, passes = 0;
  std::size_t heads_in = 0;   ///< heads over all shard maps
  std::size_t heads_out = 0;  ///< merged heads
  std::size_t harvestable = 0;
  bool geo = false;
  double seconds = 0.0;  ///< the merge itself (reading and writing excluded)
  std::vector<ShardRecord> records;
  std::vector<MergedHead> heads;        ///< the merged map (common field frame)
  std::vector<std::string> map_passes;  ///< per input map: its pass (Sighting::map indexes it)
};

/// The origin of the common field frame: the first recording's geo origin, nullopt when none has
/// one. Throws Error(recording, ...) when only some recordings have one.
std::optional<io::GeoOrigin> check_geo_origins(const BatchPlan& plan);

/// One field map to merge and where it came from.
struct MapInput {
  std::string pass;                ///< its recording's name
  std::string name;                ///< unique (a shard's name)
  std::filesystem::path map;       ///< field-map.csv (tracking/field_map_io.hpp)
  std::filesystem::path sequence;  ///< the recording (its geo_origin.yaml); empty: none
};

/// Merges `inputs` in order into the files above in `out_dir` (which must exist). Geo-referenced
/// when the inputs' sequences carry geo_origin.yaml (all or none, else Error). `records`: the
/// shards' records for passes.csv's frame counts (may be empty).
MergeSummary merge_maps(const std::vector<MapInput>& inputs, const MergeRule& rule,
                        const std::filesystem::path& out_dir, double row_gap_m, std::vector<ShardRecord> records = {});

/// Merges the shards of `plan` in `batch_dir` (all must be done) and writes the files above.
/// `row_gap_m`: assign_rows's gap. Throws Error naming a missing shard or an unreadable map.
MergeSummary merge_batch(const BatchPlan& plan, const std::filesystem::path& batch_dir, double row_gap_m = 0.3);

}  // namespace cropsight::batch
