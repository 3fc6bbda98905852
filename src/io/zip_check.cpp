#include "zip_check.hpp"

#include <zlib.h>

#include <array>
#include <cstdint>
#include <vector>

#include "cropsight/core/error.hpp"

namespace cropsight::io::detail {
namespace {

constexpr std::uint32_t kLocal = 0x04034b50, kCentral = 0x02014b50, kEnd = 0x06054b50;
constexpr std::uint32_t kEnd64 = 0x06064b50, kLocator64 = 0x07064b50;

struct Reader {
  const std::string& b;
  std::uint64_t u(std::uint64_t at, int bytes) const {  // little endian; caller checks bounds
    std::uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | std::uint8_t(b[std::size_t(at) + std::size_t(i)]);
    return v;
  }
  bool has(std::uint64_t at, std::uint64_t n) const { return at <= b.size() && n <= b.size() - at; }
};

std::uint32_t crc32_of(const char* p, std::uint64_t n) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xffffffffu;
  for (std::uint64_t i = 0; i < n; ++i) c = table[(c ^ std::uint8_t(p[i])) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

// The CRC-32 of a raw deflate stream's output; false when it does not inflate to exactly
// `expected` bytes.
bool inflated_crc32(const char* p, std::uint64_t n, std::uint64_t expected, std::uint32_t& crc_out) {
  z_stream z{};
  if (inflateInit2(&z, -MAX_WBITS) != Z_OK) return false;
  std::vector<unsigned char> out(64 * 1024);
  std::uint64_t produced = 0;
  uLong crc = ::crc32(0L, Z_NULL, 0);
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(p));
  z.avail_in = uInt(std::min<std::uint64_t>(n, 1u << 30));
  int rc = Z_OK;
  while (rc == Z_OK) {
    z.next_out = out.data(), z.avail_out = uInt(out.size());
    rc = inflate(&z, Z_NO_FLUSH);
    const std::uint64_t got = out.size() - z.avail_out;
    produced += got;
    if (produced > expected) break;  // more than the directory says: damaged
    crc = ::crc32(crc, out.data(), uInt(got));
    if (rc == Z_BUF_ERROR && got == 0) break;
  }
  inflateEnd(&z);
  crc_out = std::uint32_t(crc);
  return rc == Z_STREAM_END && produced == expected;
}

}  // namespace

void check_zip(const std::string& bytes, const std::string& where) {
  const Reader r{bytes};
  auto fail = [&](const std::string& what) { throw Error(where, "damaged model archive: " + what); };
  if (bytes.size() < 22 || r.u(0, 4) != kLocal) fail("not a zip archive");
  // The end-of-central-directory record: the last signature within its 64 KiB comment range.
  std::uint64_t end = bytes.size() - 22;
  const std::uint64_t lowest = bytes.size() > 22 + 65535 ? bytes.size() - 22 - 65535 : 0;
  while (r.u(end, 4) != kEnd) {
    if (end == lowest) fail("no end of central directory (truncated?)");
    --end;
  }
  std::uint64_t entries = r.u(end + 10, 2), dir_size = r.u(end + 12, 4), dir_at = r.u(end + 16, 4);
  if (entries == 0xffff || dir_size == 0xffffffff || dir_at == 0xffffffff) {  // zip64
    if (end < 20 || r.u(end - 20, 4) != kLocator64) fail("zip64 locator missing");
    const std::uint64_t end64 = r.u(end - 20 + 8, 8);
    if (!r.has(end64, 56) || r.u(end64, 4) != kEnd64) fail("zip64 end record missing");
    entries = r.u(end64 + 32, 8), dir_size = r.u(end64 + 40, 8), dir_at = r.u(end64 + 48, 8);
  }
  if (!r.has(dir_at, dir_size)) fail("central directory outside the file");
  std::uint64_t at = dir_at;
  for (std::uint64_t i = 0; i < entries; ++i) {
    if (!r.has(at, 46) || r.u(at, 4) != kCentral) fail("central directory entry " + std::to_string(i) + " is broken");
    const std::uint64_t method = r.u(at + 10, 2), crc = r.u(at + 16, 4), name_len = r.u(at + 28, 2),
                        extra_len = r.u(at + 30, 2), comment_len = r.u(at + 32, 2);
    std::uint64_t size = r.u(at + 20, 4), uncompressed = r.u(at + 24, 4), local = r.u(at + 42, 4);
    if (!r.has(at + 46, name_len + extra_len + comment_len))
      fail("central directory entry " + std::to_string(i) + " is broken");
    const std::string name = bytes.substr(std::size_t(at + 46), std::size_t(name_len));
    // zip64 sizes and offsets live in the extra field (header id 1), in this order when 0xffffffff.
    for (std::uint64_t x = at + 46 + name_len; x + 4 <= at + 46 + name_len + extra_len;) {
      const std::uint64_t id = r.u(x, 2), len = r.u(x + 2, 2);
      if (x + 4 + len > at + 46 + name_len + extra_len) fail("entry '" + name + "' has a broken extra field");
      if (id == 1) {
        std::uint64_t y = x + 4;
        auto take = [&](std::uint64_t& field) {
          if (field != 0xffffffff) return;
          if (y + 8 > x + 4 + len) fail("entry '" + name + "' has a broken zip64 field");
          field = r.u(y, 8), y += 8;
        };
        take(uncompressed);
        take(size);  // compressed size: the bytes stored
        take(local);
      }
      x += 4 + len;
    }
    if (method != 0 && method != 8) fail("entry '" + name + "' uses an unknown compression method");
    if (!r.has(local, 30) || r.u(local, 4) != kLocal) fail("entry '" + name + "' has no local header");
    const std::uint64_t data = local + 30 + r.u(local + 26, 2) + r.u(local + 28, 2);
    if (!r.has(data, size)) fail("entry '" + name + "' lies outside the file (truncated?)");
    std::uint32_t sum = 0;
    if (method == 0) {
      sum = crc32_of(bytes.data() + data, size);
    } else if (!inflated_crc32(bytes.data() + data, size, uncompressed, sum)) {
      fail("entry '" + name + "' does not inflate to its size");
    }
    if (sum != crc) fail("entry '" + name + "' fails its CRC-32 check");
    at += 46 + name_len + extra_len + comment_len;
  }
}

}  // namespace cropsight::io::detail
