#pragma once
// import --timestamps (internal to io): the times of a recorder's frames from a CSV, for layouts
// whose file names carry frame numbers only.
#include <filesystem>
#include <vector>

#include "cropsight/io/recording_import.hpp"

namespace cropsight::io::detail {

/// Seconds for each of `frames` (in their order) from a CSV whose header names the columns
/// `frame` (the number in the frame files' names) and `timestamp` (seconds; other columns are
/// ignored, '#' lines are comments). Throws Error(path, ...) for a missing column, a non-finite
/// number, a frame listed twice or not at all, or times that do not increase with the frames.
std::vector<double> frame_times_from_csv(const std::filesystem::path& path, const std::vector<RecordingFile>& frames);

}  // namespace cropsight::io::detail
