#include "cropsight/stereo/stereo_io.hpp"
#include "cropsight/io/file_names.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cv_convert.hpp"
#include "io/decode_image.hpp"

namespace cropsight::stereo {

namespace fs = std::filesystem;

namespace {

// The file as stored (depth and channels untouched), or Error(path, ...).
cv::Mat read_unchanged(const fs::path& path, const char* what) {
  const cv::Mat m = io::decode_image_file(path, cv::IMREAD_UNCHANGED);  // names missing, folder, truncated
  if (m.empty()) throw Error(path.string(), std::string("cannot decode ") + what);
  return m;
}

int bits_of(const cv::Mat& m) {
  switch (m.depth()) {
    case CV_8U:
    case CV_8S:
      return 8;
    case CV_16U:
    case CV_16S:
      return 16;
    default:
      return 32;
  }
}

cv::Mat read_8bit(const fs::path& path) {
  cv::Mat m = read_unchanged(path, "image");
  if (m.depth() != CV_8U)
    throw Error(path.string(), "is a " + std::to_string(bits_of(m)) + "-bit image; expected 8 bits per channel");
  if (m.channels() != 1 && m.channels() != 3 && m.channels() != 4)
    throw Error(path.string(), "has " + std::to_string(m.channels()) + " channels; expected 1, 3 or 4");
  return m;
}

ColorImage to_rgb(const cv::Mat& m) {
  cv::Mat rgb;
  cv::cvtColor(m, rgb,
               m.channels() == 1   ? cv::COLOR_GRAY2RGB
               : m.channels() == 4 ? cv::COLOR_BGRA2RGB
                                   : cv::COLOR_BGR2RGB);
  return detail::to_color(rgb);
}

using io::lower_extension;

}  // namespace

ColorImage read_color(const fs::path& path) { return to_rgb(read_8bit(path)); }

GrayImage read_gray(const fs::path& path) {
  const cv::Mat m = read_8bit(path);
  if (m.channels() == 1) return detail::to_gray(m);
  cv::Mat g;
  cv::cvtColor(m, g, m.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return detail::to_gray(g);
}

std::pair<ColorImage, ColorImage> read_color_pair(const fs::path& left, const fs::path& right) {
  const cv::Mat l = read_8bit(left), r = read_8bit(right);
  auto kind = [](const cv::Mat& m) { return m.channels() == 1 ? std::string("grey") : std::string("colour"); };
  if (kind(l) != kind(r))
    throw Error(right.string(), "is a " + kind(r) + " image but " + left.string() + " is " + kind(l) +
                                    "; both views must be grey or both colour");
  if (l.size() != r.size())
    throw Error(right.string(), "size " + std::to_string(r.cols) + "x" + std::to_string(r.rows) + " differs from " +
                                    left.string() + " (" + std::to_string(l.cols) + "x" + std::to_string(l.rows) + ")");
  return {to_rgb(l), to_rgb(r)};
}

DisparityImage read_disparity(const fs::path& path, double scale, int bits) {
  const cv::Mat m = read_unchanged(path, "disparity image");
  if (m.channels() != 1)
    throw Error(path.string(), "disparity image must have one channel, has " + std::to_string(m.channels()));
  if (m.depth() != CV_8U && m.depth() != CV_16U)
    throw Error(path.string(), "disparity image must be 8- or 16-bit unsigned");
  if (bits != 0 && bits_of(m) != bits)
    throw Error(path.string(), "is a " + std::to_string(bits_of(m)) + "-bit disparity image; expected " +
                                   std::to_string(bits) + "-bit");
  cv::Mat f;
  m.convertTo(f, CV_32F);
  DisparityImage out(f.cols, f.rows);
  for (int y = 0; y < f.rows; ++y)
    for (int x = 0; x < f.cols; ++x) {
      const float v = f.at<float>(y, x);
      out.at(x, y) = v > 0 ? float(v / scale) : std::nanf("");
    }
  return out;
}

Image<float> read_pfm(const fs::path& path) {
  const std::string where = path.string();
  if (!fs::exists(path)) throw Error(where, "file not found");
  if (fs::is_directory(path)) throw Error(where, "is a folder, expected a PFM file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(where, "cannot open");
  std::string magic;
  in >> magic;
  if (magic == "PF") throw Error(where, "is a colour PFM (PF); a disparity map is one-channel (Pf)");
  if (magic != "Pf") throw Error(where, "not a PFM file (expected the header 'Pf')");
  long w = 0, h = 0;
  double scale = 0;
  if (!(in >> w >> h >> scale)) throw Error(where, "PFM header lacks 'width height scale'");
  if (w < 1 || h < 1 || w > 65535 || h > 65535)
    throw Error(where, "PFM size " + std::to_string(w) + "x" + std::to_string(h) + " outside 1..65535");
  if (scale == 0 || !std::isfinite(scale)) throw Error(where, "PFM scale must be a non-zero number");
  in.get();  // the single whitespace character that ends the header
  // The data's size is checked against the file before anything is allocated: a 20-byte header
  // can claim 65535 x 65535 floats (16 GiB; fuzzing finding 30).
  const std::uintmax_t expected = std::uintmax_t(w) * std::uintmax_t(h) * sizeof(float);
  const std::streamoff at = in.tellg();
  const std::uintmax_t left = at < 0 ? 0 : fs::file_size(path) - std::min(fs::file_size(path), std::uintmax_t(at));
  if (left < expected)
    throw Error(where, "PFM data truncated: expected " + std::to_string(w) + "x" + std::to_string(h) + " floats, got " +
                           std::to_string(left / sizeof(float)));
  std::vector<float> raw(std::size_t(w) * std::size_t(h));
  in.read(reinterpret_cast<char*>(raw.data()), std::streamsize(raw.size() * sizeof(float)));
  if (in.gcount() != std::streamsize(raw.size() * sizeof(float)))
    throw Error(where, "PFM data truncated: expected " + std::to_string(w) + "x" + std::to_string(h) + " floats, got " +
                           std::to_string(in.gcount() / long(sizeof(float))));
  // The sign of the scale gives the byte order; swap when it differs from this machine's.
  const bool little = scale < 0;
  if (little != (std::endian::native == std::endian::little))
    for (float& f : raw) {
      std::uint32_t u;
      std::memcpy(&u, &f, 4);
      u = __builtin_bswap32(u);
      std::memcpy(&f, &u, 4);
    }
  Image<float> out{static_cast<int>(w), static_cast<int>(h)};
  for (long y = 0; y < h; ++y)
    for (long x = 0; x < w; ++x) {
      const float v = raw[std::size_t(h - 1 - y) * std::size_t(w) + std::size_t(x)];  // bottom row first
      out.at(int(x), int(y)) = std::isfinite(v) ? v : std::nanf("");
    }
  return out;
}

DisparityImage read_ground_truth(const fs::path& path, double scale) {
  if (lower_extension(path) != ".pfm") return read_disparity(path, scale, 0);
  DisparityImage d = read_pfm(path);
  for (float& v : d.data) v = std::isfinite(v) && v > 0 ? float(v / scale) : std::nanf("");
  return d;
}

void write_pfm(const fs::path& path, const Image<float>& values) {
  io::write_atomic_with(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << "Pf\n" << values.width << " " << values.height << "\n-1\n";
    for (int y = values.height - 1; y >= 0; --y)
      for (int x = 0; x < values.width; ++x) {
        float v = values.at(x, y);
        std::uint32_t u;
        std::memcpy(&u, &v, 4);
        if constexpr (std::endian::native != std::endian::little) u = __builtin_bswap32(u);
        out.write(reinterpret_cast<const char*>(&u), 4);
      }
    if (!out) throw Error(path.string(), "cannot write PFM file");
  });
}

void check_image_output(const fs::path& path, const std::string& option, bool sixteen_bit) {
  const std::string where = path.string();
  if (path.empty()) throw Error(option, "empty file name");
  if (fs::is_directory(path) || !path.has_filename())
    throw Error(where, "is a folder; " + option + " needs an image file name such as out.png");
  const std::string ext = lower_extension(path);
  // Lossless formats only: a mask or disparity stored as JPEG changes its values. Of these only
  // PNG, TIFF and PGM hold 16-bit samples.
  const bool ok = ext == ".png" || ext == ".tif" || ext == ".tiff" || ext == ".pgm" || (!sixteen_bit && ext == ".bmp");
  const std::string allowed = sixteen_bit ? ".png, .tif, .tiff or .pgm (16-bit)" : ".png, .tif, .tiff, .pgm or .bmp";
  if (!ok)
    throw Error(where, option + " must end in " + allowed + ", got " +
                           (ext.empty() ? std::string("no extension") : "'" + ext + "'"));
  if (!cv::haveImageWriter(where)) throw Error(where, "this OpenCV build cannot write " + ext + " files");
}

DepthImage scaled_disparity(const DisparityImage& d, double scale) {
  DepthImage out(d.width, d.height, 0);
  for (std::size_t i = 0; i < d.data.size(); ++i) {
    const float v = d.data[i];
    out.data[i] = std::isnan(v) || v <= 0 ? 0 : std::uint16_t(std::min(65535.0, std::round(double(v) * scale)));
  }
  return out;
}

void write_disparity_png(const fs::path& path, const DisparityImage& d, double scale) {
  const DepthImage scaled = scaled_disparity(d, scale);
  const cv::Mat m(d.height, d.width, CV_16U, const_cast<std::uint16_t*>(scaled.data.data()));
  io::write_atomic_with(path, [&](const fs::path& tmp) {
    if (!cv::imwrite(tmp.string(), m)) throw Error(path.string(), "cannot write image");
  });
}

void write_color_png(const fs::path& path, const ColorImage& image) {
  cv::Mat bgr;
  cv::cvtColor(detail::view(image), bgr, cv::COLOR_RGB2BGR);
  io::write_atomic_with(path, [&](const fs::path& tmp) {
    if (!cv::imwrite(tmp.string(), bgr)) throw Error(path.string(), "cannot write image");
  });
}

void write_gray_png(const fs::path& path, const GrayImage& image) {
  io::write_atomic_with(path, [&](const fs::path& tmp) {
    if (!cv::imwrite(tmp.string(), detail::view(image))) throw Error(path.string(), "cannot write image");
  });
}

}  // namespace cropsight::stereo
