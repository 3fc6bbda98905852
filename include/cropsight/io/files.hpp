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
/// Puts the finished directory `tmp` in place of `dir`. A previous `dir` is moved aside first
/// and removed only once the new one is in place, so a failure leaves the old contents. Throws
/// Error(dir, "cannot write the <what>: ...").
void replace_directory(const std::filesystem::path& tmp, const std::filesystem::path& dir,
                       const std::string& what = "directory");

/// An empty temporary sibling of `dir` (".NAME.tmp-PID-RANDOM"), for outputs that must appear
/// whole (write into it, then replace_directory and release). Removed by the destructor unless
/// released, so a failed run leaves nothing that looks complete.
class TempDirectory {
 public:
  explicit TempDirectory(const std::filesystem::path& dir);
  ~TempDirectory();
  TempDirectory(const TempDirectory&) = delete;
  TempDirectory& operator=(const TempDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }
  /// Moves the temporary in place of `dir` (replace_directory); nothing is removed afterwards.
  void commit(const std::string& what = "directory");

 private:
  std::filesystem::path dir_, path_;
  bool committed_ = false;
};

/// Throws Error(FOLDER, ...) when `path` (a file or folder to write) could not be created: the
/// nearest existing folder above it is a file, or is not writable. Creates nothing. Called before
/// long work, so that a bad --out costs no run and prints no progress before its error line.
void check_can_create(const std::filesystem::path& path);

/// Whole file as a string. Throws Error(path, "cannot read ...").
std::string read_file(const std::filesystem::path& path);

}  // namespace cropsight::io
