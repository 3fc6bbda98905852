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
/// Puts the finished directory `tmp` in place of `dir`. A previous `dir` is swapped with `tmp` in
/// one step (renameat2 RENAME_EXCHANGE), so `dir` always holds the old or the new contents, even
/// when the process is killed in between; the old contents (now at `tmp`) are removed afterwards.
/// Where the file system cannot swap, the old `dir` is moved aside first and removed only once the
/// new one is in place (a kill in between leaves no `dir`, the old contents at a temporary name).
/// A failure leaves the old contents. Throws Error(dir, "cannot write the <what>: ...").
void replace_directory(const std::filesystem::path& tmp, const std::filesystem::path& dir,
                       const std::string& what = "directory");

/// A new name beside `path` for a temporary of it: ".NAME.tmp-PID-RANDOM" (this process's id).
std::filesystem::path temporary_sibling(const std::filesystem::path& path);
/// Removes what writers of `path` killed by a signal (which cannot unwind) left beside it: siblings
/// ".NAME.tmp-PID-..." (and ".NAME.old-PID-...", older builds' name) whose process PID no longer
/// exists. Temporaries of a live process, this one included, are left alone. Best effort: errors
/// are ignored.
void remove_stale_temporaries(const std::filesystem::path& path);

/// An empty temporary sibling of `dir` (temporary_sibling), for outputs that must appear whole
/// (write into it, then commit). Removed by the destructor unless committed, so a failed run
/// leaves nothing that looks complete; the constructor removes the stale temporaries of `dir`
/// that killed runs left (remove_stale_temporaries).
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

/// Whole file as a string. Throws Error(path, "cannot read ...").
std::string read_file(const std::filesystem::path& path);

}  // namespace cropsight::io
