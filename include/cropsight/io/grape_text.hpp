#pragma once
// The text format of the grape bunch dataset (Luo et al.): one point per line, ten
// whitespace-separated numbers "x y z nx ny nz r g b label" — position (unit-sphere scale),
// unit normal, colour in [0, 1], integer class label stored as a float.
#include <filesystem>
#include <vector>

#include "cropsight/core/cloud.hpp"

namespace cropsight::io {

/// Reads one cloud. Fills points, normals, colors and labels. Throws Error whose message names
/// the file and the 1-based line ("FILE: line 12: expected 10 numbers, got 9").
Cloud read_grape_text(const std::filesystem::path& path);

/// Writes `cloud` in the same format (zero normals / colours where absent, label -1 → 0 never:
/// a cloud without labels is written with label 0). Atomic: temporary name, then rename.
void write_grape_text(const std::filesystem::path& path, const Cloud& cloud);

/// The dataset's cloud files in `dir` (directly, or under dir/points/), sorted by name.
/// Throws Error(dir, ...) when the folder is missing or holds no .txt file.
std::vector<std::filesystem::path> list_grape_clouds(const std::filesystem::path& dir);

}  // namespace cropsight::io
