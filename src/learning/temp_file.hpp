#pragma once
// libsvm reads and writes models only through file names; this gives it a private temporary
// file that goes when the object goes out of scope. It is an anonymous in-memory file (memfd),
// named by its /proc/self/fd path, so a process killed while loading a model leaves nothing in
// /tmp (kill safety); a named file in the temporary folder only where memfd is missing.
#include <filesystem>
#include <string>

namespace cropsight::learning::detail {

class TempFile {
 public:
  TempFile();
  ~TempFile();
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::filesystem::path& path() const { return path_; }
  /// Replaces the file's content with `bytes`; throws Error naming the file on failure.
  void write(const std::string& bytes) const;

 private:
  std::filesystem::path path_;
  int fd_ = -1;  // the memfd, or -1 for a named file
};

/// Standard base64 (RFC 4648) of raw bytes, and back; decode throws Error(where, ...) on bad input.
std::string base64_encode(const void* data, std::size_t size);
std::string base64_decode(const std::string& text, const std::string& where);

}  // namespace cropsight::learning::detail
