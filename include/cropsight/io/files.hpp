#pragma once
// Small file utilities shared by every writer.
#include <filesystem>
#include <functional>
#include <string>

namespace cropsight::io {

/// Writes `content` to `path` atomically: a temporary file in the same directory, then rename.
/// Creates parent directories. Throws Error(path, ...) on failure.
void write_file_atomic(const std::filesystem::path& path, const std::string& content);
/// Like write_file_atomic, but `write` writes the temporary file itself (given its path); used for
/// library writers (PCL, OpenCV) that need a file name.
void write_atomic_with(const std::filesystem::path& path,
                       const std::function<void(const std::filesystem::path& tmp)>& write);
/// Whole file as a string. Throws Error(path, "cannot read ...").
std::string read_file(const std::filesystem::path& path);

}  // namespace cropsight::io
