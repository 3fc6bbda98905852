#pragma once
// poses.csv and groundtruth.json of the sequence format (internal to io).
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/io/sequence.hpp"

namespace cropsight::io::detail {

/// Parses poses.csv; `frames` is the depth frame count the rows must match.
std::vector<CameraPose> read_poses_csv(const std::filesystem::path& path, int frames);
std::string format_poses_csv(const std::vector<CameraPose>& poses);
/// timestamps.csv: `frame,timestamp` rows, the time of each frame of a sequence without poses.
std::vector<double> read_timestamps_csv(const std::filesystem::path& path, int frames);
std::string format_timestamps_csv(const std::vector<double>& timestamps);

GroundTruth read_groundtruth_json(const std::filesystem::path& path);
/// Throws Error(where, ...) for non-finite values or ids outside 1..65535.
std::string format_groundtruth_json(const GroundTruth& truth, const std::string& where);

}  // namespace cropsight::io::detail
