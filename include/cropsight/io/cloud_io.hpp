#pragma once
// Point-cloud files through PCL (PCD, PLY): organised clouds keep width×height.
// All writers are atomic (temporary name, then rename).
#include <filesystem>

#include "cropsight/core/cloud.hpp"
#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::io {

/// Format chosen by extension (.pcd or .ply); colour written when the cloud has it.
void write_cloud(const std::filesystem::path& path, const OrganizedCloud& cloud, bool binary = true);
void write_cloud(const std::filesystem::path& path, const Cloud& cloud, bool binary = true);
/// Reads an organised cloud (.pcd/.ply with height > 1). Throws Error(path, ...) otherwise.
OrganizedCloud read_organized_cloud(const std::filesystem::path& path);
/// Reads any cloud, dropping non-finite points.
Cloud read_cloud(const std::filesystem::path& path);

}  // namespace cropsight::io
