#pragma once
// The merge of many passes' broccoli field maps into one map (cropsight merge, and batch's last
// step). The maps must already be in one field frame (metres; batch converts each recording's
// frame through WGS84 when the recordings carry geo_origin.yaml, io/geo_origin.hpp).
//
// Rule — the temporal filter's association (tracking/temporal_filter.hpp, step 3) applied to maps
// instead of frames: the maps are taken in order; the heads of the next map are paired with the
// merged heads within MergeRule::association_radius_m (the pipeline's tracking.association_radius_m,
// 0.05 m by default; 3D distance), one-to-one, closest pairs first (ties: lower indices first), so
// two heads closer than the radius stay two heads. A paired head joins its merged head: position
// averaged over frames_seen, diameters averaged over the frames of sized sightings (diameter > 0);
// an unpaired head starts a merged head. Harvestable = the merged diameter inside the market
// window [market_min_mm, market_max_mm] (measure::HeadSizer's rule). The result does not depend on
// where the maps were computed, so equal maps give equal bytes.
//
// Cost: a uniform grid of cell = radius over the merged heads; each map costs O(its heads ×
// neighbours), so the whole merge is O(total heads) for fields of separate plants.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "cropsight/batch/plan.hpp"
#include "cropsight/tracking/track_results.hpp"

namespace cropsight::batch {

/// One map to merge: a shard's heads, in the common field frame.
struct PassMap {
  std::string pass;   ///< the recording (several shards may share it)
  std::string shard;  ///< the shard's name (unique)
  std::vector<tracking::TrackedHead> heads;
};

/// One map's head that a merged head took in.
struct Sighting {
  std::size_t map = 0;  ///< index in the merge's input
  int head_id = 0, first_frame = 0, last_frame = 0, frames_seen = 0;
};

struct MergedHead {
  int id = 0;                                          ///< 1-based, in order of creation
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< common field frame, metres
  double diameter_mm = 0.0, bbox_mm = 0.0, hull_mm = 0.0;
  int frames_seen = 0;
  int sized_frames = 0;  ///< frames behind the diameters (sightings with diameter > 0)
  bool harvestable = false;
  int row = 0;  ///< 1-based row (assign_rows), 0 before
  std::vector<Sighting> seen_by;
};

/// Merges `maps` in order by the rule at the top of this file.
std::vector<MergedHead> merge_field_maps(const std::vector<PassMap>& maps, const MergeRule& rule);

/// Numbers the rows of a field whose rows run along field x: heads sorted by y, a new row where
/// the gap to the previous head's y exceeds `row_gap_m` (e.g. half the row spacing). Rows count
/// from 1 at the smallest y.
void assign_rows(std::vector<MergedHead>& heads, double row_gap_m);

}  // namespace cropsight::batch
