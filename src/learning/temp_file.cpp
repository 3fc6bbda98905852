#include "learning/temp_file.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <system_error>

#include "cropsight/core/error.hpp"

namespace cropsight::learning::detail {

TempFile::TempFile() {
  fd_ = ::memfd_create("cropsight-model", MFD_CLOEXEC);
  if (fd_ >= 0) {
    path_ = "/proc/self/fd/" + std::to_string(fd_);
    std::error_code ec;
    if (std::filesystem::exists(path_, ec)) return;  // /proc is mounted: libsvm can open it by name
    ::close(fd_);
    fd_ = -1;
  }
  std::string templ = (std::filesystem::temp_directory_path() / "cropsight-model-XXXXXX").string();
  const int fd = ::mkstemp(templ.data());
  if (fd < 0) throw Error(templ, "cannot create a temporary file");
  ::close(fd);
  path_ = templ;
}

TempFile::~TempFile() {
  if (fd_ >= 0) {
    ::close(fd_);
    return;
  }
  std::error_code ec;
  std::filesystem::remove(path_, ec);
}

void TempFile::write(const std::string& bytes) const {
  std::ofstream out(path_, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out.flush()) throw Error(path_.string(), "cannot write the temporary model file");
}

namespace {
constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
}

std::string base64_encode(const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3) {
    const unsigned v =
        unsigned(p[i]) << 16 | (i + 1 < size ? unsigned(p[i + 1]) << 8 : 0u) | (i + 2 < size ? unsigned(p[i + 2]) : 0u);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < size ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < size ? kAlphabet[v & 63] : '=';
  }
  return out;
}

std::string base64_decode(const std::string& text, const std::string& where) {
  auto value = [&](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    throw Error(where, "invalid base64 character");
  };
  if (text.size() % 4 != 0) throw Error(where, "base64 length is not a multiple of 4");
  std::string out;
  out.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    const int pad = (text[i + 3] == '=') + (text[i + 2] == '=');
    if (pad && i + 4 != text.size()) throw Error(where, "base64 padding inside the data");
    const unsigned v = unsigned(value(text[i])) << 18 | unsigned(value(text[i + 1])) << 12 |
                       (pad >= 2 ? 0u : unsigned(value(text[i + 2])) << 6) |
                       (pad >= 1 ? 0u : unsigned(value(text[i + 3])));
    out += char((v >> 16) & 255);
    if (pad < 2) out += char((v >> 8) & 255);
    if (pad < 1) out += char(v & 255);
  }
  return out;
}

}  // namespace cropsight::learning::detail
