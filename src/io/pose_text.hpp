#pragma once
// Shared by the pose file readers (internal to io): splitting lines and checking a track.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "cropsight/io/pose_track.hpp"

namespace cropsight::io::detail {

/// The fields of `line` split at `sep`, or at runs of spaces and tabs when `sep` is ' '.
std::vector<std::string_view> pose_fields(std::string_view line, char sep);
/// A finite number, or Error(path, "line N: ...") naming the column.
double pose_number(std::string_view text, const char* column, int line, const std::filesystem::path& path);
/// Appends a pose after checking that its time increases and its quaternion is a unit one.
void add_pose(PoseTrack& track, TimedPose pose, int line, const std::filesystem::path& path);

PoseTrack read_pose_csv(const std::filesystem::path& path, const std::string& text);
PoseTrack read_pose_tum(const std::filesystem::path& path, const std::string& text);
bool looks_like_pose_csv(const std::filesystem::path& path, std::string_view first_line);
bool looks_like_pose_tum(const std::filesystem::path& path, std::string_view first_line);
PoseTrack read_pose_gnss(const std::filesystem::path& path, const std::string& text);
bool looks_like_pose_gnss(const std::filesystem::path& path, std::string_view first_line);

}  // namespace cropsight::io::detail
