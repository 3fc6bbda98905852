#pragma once
// libsvm reads and writes models only through file names; this gives it a private temporary
// file that is removed when the object goes out of scope.
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

 private:
  std::filesystem::path path_;
};

/// Standard base64 (RFC 4648) of raw bytes, and back; decode throws Error(where, ...) on bad input.
std::string base64_encode(const void* data, std::size_t size);
std::string base64_decode(const std::string& text, const std::string& where);

}  // namespace cropsight::learning::detail
