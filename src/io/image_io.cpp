#include "cropsight/io/image_io.hpp"
#include "cropsight/io/file_names.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "io/decode_image.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {

std::string describe(const cv::Mat& m) {
  const int d = m.depth();
  const char* bits = d == CV_8U    ? "8-bit"
                     : d == CV_16U ? "16-bit"
                     : d == CV_8S  ? "8-bit signed"
                     : d == CV_16S ? "16-bit signed"
                     : d == CV_32F ? "32-bit float"
                                   : "other-depth";
  return std::string(bits) + " " + std::to_string(m.channels()) + "-channel";
}

// True when `b` starts as a PNG and its chunks (4-byte big-endian length, type, data, CRC) run
// to an IEND chunk inside the file. CRCs are left to libpng.
bool png_complete(const std::string& b) {
  static const char kSig[] = "\x89PNG\r\n\x1a\n";
  if (b.compare(0, 8, kSig, 8) != 0) return true;  // not a PNG: its decoder decides
  std::size_t at = 8;
  while (at + 12 <= b.size()) {
    const auto byte = [&](std::size_t i) { return std::uint32_t(static_cast<unsigned char>(b[at + i])); };
    const std::uint64_t len = (byte(0) << 24) | (byte(1) << 16) | (byte(2) << 8) | byte(3);
    if (b.compare(at + 4, 4, "IEND") == 0) return true;
    at += 12 + len;
  }
  return false;
}

cv::Mat load_image(const fs::path& path) {
  const cv::Mat m = decode_image_file(path, cv::IMREAD_UNCHANGED);
  if (m.empty()) throw Error(path.string(), "cannot decode image (damaged, truncated or not an image file)");
  return m;
}

// Fixed PNG parameters: equal pixels give equal bytes (no timestamps in OpenCV's PNG writer).
const std::vector<int> kPngParams = {cv::IMWRITE_PNG_COMPRESSION, 3, cv::IMWRITE_PNG_STRATEGY,
                                     cv::IMWRITE_PNG_STRATEGY_DEFAULT};

std::string encode(const cv::Mat& m, const std::string& ext, const std::string& where) {
  if (m.empty()) throw Error(where, "cannot encode an empty image");
  std::vector<uchar> buf;
  bool ok = false;
  try {
    ok = cv::imencode(ext, m, buf, ext == ".png" ? kPngParams : std::vector<int>{});
  } catch (const cv::Exception& e) {
    throw Error(where, std::string("cannot encode image: ") + e.what());
  }
  if (!ok) throw Error(where, "cannot encode image as " + ext);
  return std::string(reinterpret_cast<const char*>(buf.data()), buf.size());
}

std::string extension_of(const fs::path& path) {
  std::string ext = lower_extension(path);
  if (ext.empty()) throw Error(path.string(), "image file name needs an extension (.png)");
  return ext;
}

cv::Mat wrap_u16(const Image<std::uint16_t>& img) {
  return cv::Mat(img.height, img.width, CV_16UC1, const_cast<std::uint16_t*>(img.data.data()));
}
cv::Mat wrap_gray(const GrayImage& img) {
  return cv::Mat(img.height, img.width, CV_8UC1, const_cast<std::uint8_t*>(img.data.data()));
}
cv::Mat to_bgr(const ColorImage& img) {
  static_assert(sizeof(Rgb8) == 3, "Rgb8 must be packed");
  cv::Mat rgb(img.height, img.width, CV_8UC3, const_cast<Rgb8*>(img.data.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  return bgr;
}
void check_size(const std::string& where, int w, int h, std::size_t n) {
  if (w <= 0 || h <= 0 || std::size_t(w) * std::size_t(h) != n) throw Error(where, "image is empty or inconsistent");
}

}  // namespace

namespace {
// libjpeg decodes a JPEG cut short without a word through OpenCV, filling the missing rows with
// grey: a frame damaged in copying would pass as a picture. A whole JPEG ends with the EOI marker
// FF D9; some writers pad after it, so the last 32 bytes are searched.
bool jpeg_complete(const std::string& b) {
  const bool jpeg =
      b.size() >= 3 && std::uint8_t(b[0]) == 0xFF && std::uint8_t(b[1]) == 0xD8 && std::uint8_t(b[2]) == 0xFF;
  if (!jpeg) return true;
  for (std::size_t i = b.size() - 1; i >= 1 && i + 32 >= b.size(); --i)
    if (std::uint8_t(b[i - 1]) == 0xFF && std::uint8_t(b[i]) == 0xD9) return true;
  return false;
}
}  // namespace

std::string read_image_file(const fs::path& path) {
  // The error-code overloads: a name the system refuses (too long, a symlink loop) is an Error
  // naming it, not a std::filesystem_error (fuzzing finding 21).
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (st.type() == fs::file_type::not_found) throw Error(path.string(), "file not found");
  if (ec) throw Error(path.string(), "cannot access: " + ec.message());
  // Named before reading: a permission or directory problem is fixed differently from a damaged file.
  if (fs::is_directory(st)) throw Error(path.string(), "is a directory, not an image");
  std::string bytes = read_file(path);
  if (bytes.empty()) throw Error(path.string(), "empty file, not an image");
  if (!png_complete(bytes)) throw Error(path.string(), "truncated PNG (its chunks end before IEND)");
  if (!jpeg_complete(bytes)) throw Error(path.string(), "truncated JPEG (no end-of-image marker)");
  return bytes;
}

Image<std::uint16_t> read_u16(const fs::path& path) {
  const cv::Mat m = load_image(path);
  if (m.depth() != CV_16U || m.channels() != 1)
    throw Error(path.string(), "expected a 16-bit single-channel image, got " + describe(m));
  Image<std::uint16_t> out(m.cols, m.rows);
  for (int v = 0; v < m.rows; ++v) std::memcpy(out.row(v), m.ptr<std::uint16_t>(v), std::size_t(m.cols) * 2);
  return out;
}

ColorImage read_color(const fs::path& path) {
  const cv::Mat m = load_image(path);
  if (m.depth() != CV_8U || (m.channels() != 3 && m.channels() != 1))
    throw Error(path.string(), "expected an 8-bit colour (3-channel) or grey image, got " + describe(m));
  cv::Mat rgb;
  cv::cvtColor(m, rgb, m.channels() == 1 ? cv::COLOR_GRAY2RGB : cv::COLOR_BGR2RGB);
  ColorImage out(rgb.cols, rgb.rows);
  for (int v = 0; v < rgb.rows; ++v) std::memcpy(out.row(v), rgb.ptr<std::uint8_t>(v), std::size_t(rgb.cols) * 3);
  return out;
}

GrayImage read_gray(const fs::path& path) {
  const cv::Mat m = load_image(path);
  if (m.depth() != CV_8U || m.channels() != 1)
    throw Error(path.string(), "expected an 8-bit single-channel image, got " + describe(m));
  GrayImage out(m.cols, m.rows);
  for (int v = 0; v < m.rows; ++v) std::memcpy(out.row(v), m.ptr<std::uint8_t>(v), std::size_t(m.cols));
  return out;
}

void write_u16(const fs::path& path, const Image<std::uint16_t>& img) {
  check_size(path.string(), img.width, img.height, img.size());
  write_file_atomic(path, encode(wrap_u16(img), extension_of(path), path.string()));
}

void write_color(const fs::path& path, const ColorImage& img) {
  check_size(path.string(), img.width, img.height, img.size());
  write_file_atomic(path, encode(to_bgr(img), extension_of(path), path.string()));
}

void write_gray(const fs::path& path, const GrayImage& img) {
  check_size(path.string(), img.width, img.height, img.size());
  write_file_atomic(path, encode(wrap_gray(img), extension_of(path), path.string()));
}

std::string encode_png(const ColorImage& img) {
  check_size("png", img.width, img.height, img.size());
  return encode(to_bgr(img), ".png", "png");
}
std::string encode_png(const GrayImage& img) {
  check_size("png", img.width, img.height, img.size());
  return encode(wrap_gray(img), ".png", "png");
}
std::string encode_png(const Image<std::uint16_t>& img) {
  check_size("png", img.width, img.height, img.size());
  return encode(wrap_u16(img), ".png", "png");
}

}  // namespace cropsight::io
