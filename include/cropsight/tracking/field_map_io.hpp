#pragma once
// The field map as CSV (`cropsight detect broccoli --track --map map.csv`):
//
//   id,x_m,y_m,z_m,diameter_mm,bbox_diameter_mm,hull_diameter_mm,frames_seen,first_frame,last_frame,score,harvestable
//
// one row per mapped head; x, y, z in metres in the field frame (tracking/field_transform.hpp);
// diameter_mm = the configured estimator after bias correction, bbox_/hull_diameter_mm = the raw
// estimators averaged over the frames (hull 0 when not computed); harvestable = 0 or 1.
#include <filesystem>
#include <vector>

#include "cropsight/tracking/temporal_filter.hpp"

namespace cropsight::tracking {

/// CSV text of the map.
std::string field_map_csv(const std::vector<TrackedHead>& heads);
/// Writes the map atomically (temporary file, then rename).
void write_field_map(const std::filesystem::path& path, const std::vector<TrackedHead>& heads);
/// Reads a map written by write_field_map; throws Error("FILE line N", ...) on a malformed row.
std::vector<TrackedHead> read_field_map(const std::filesystem::path& path);

}  // namespace cropsight::tracking
