#pragma once
// The one way the library decodes an image file with OpenCV (io, stereo): the bytes come from
// io::read_image_file (which names a missing, folder, empty or truncated file first), then
// cv::imdecode. Internal header: OpenCV stays out of the public ones.
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <string_view>

#include "cropsight/core/error.hpp"
#include "cropsight/io/image_io.hpp"

namespace cropsight::io {

/// Whether OpenCV 4.6 decodes this content only from a file (PFM, Radiance HDR, OpenEXR: the
/// decoders without memory input), recognised by its signature as OpenCV does, whatever the
/// file's extension. cv::imdecode copies such bytes to a temporary file (/tmp/__opencv_temp.*,
/// or $OPENCV_TEMP_PATH) and leaves it behind when the header is bad (an OpenCV assertion on the
/// size skips its clean-up): one stray file per damaged image read (fuzzing finding 20,
/// docs/reliability.md). cv::imread reads the file itself and leaves nothing.
inline bool decoded_only_from_files(std::string_view bytes) {
  for (std::string_view signature : {"Pf", "PF", "#?RADIANCE", "#?RGBE", "\x76\x2f\x31\x01"})
    if (bytes.substr(0, signature.size()) == signature) return true;
  return false;
}

/// Whether the content starts with the signature of a format cropsight reads: PNG, JPEG, BMP,
/// TIFF, PNM (P1-P7), PFM, WebP, Radiance HDR, OpenEXR. The other decoders OpenCV was built with
/// are never offered a file: Debian's OpenCV reads DICOM through GDCM, which aborts the process on
/// a damaged header (an assert, fuzzing finding 29), and JPEG 2000, Sun raster and the rest are
/// not formats of a camera, a robot or a data set cropsight knows.
///
/// OpenCV picks a decoder by asking each in turn whether it claims the first bytes, and some claim
/// bytes far from the start: GDCM "DICM" at 128, GDAL "NITF" at 0 and "DTED" at 140. Such content
/// is refused whatever it starts with. Otherwise a start that one of OpenCV's own checks rejects
/// (a PFM "Pf" with no whitespace after it, which OpenCV's PFM check requires) reached GDCM
/// further down the list (fuzzing finding 31).
inline bool supported_image_signature(std::string_view b) {
  const auto starts = [&](std::string_view sig) { return b.substr(0, sig.size()) == sig; };
  using namespace std::string_view_literals;
  if ((b.size() >= 132 && b.substr(128, 4) == "DICM"sv) || starts("NITF"sv) ||
      (b.size() >= 144 && b.substr(140, 4) == "DTED"sv))
    return false;
  if (starts("\x89PNG\r\n\x1a\n"sv) || starts("\xff\xd8\xff"sv) || starts("BM"sv) || starts("II*\0"sv) ||
      starts("MM\0*"sv))
    return true;
  if (b.size() >= 2 && b[0] == 'P' && b[1] >= '1' && b[1] <= '7') return true;  // PBM, PGM, PPM, PAM
  if (b.size() >= 12 && starts("RIFF"sv) && b.substr(8, 4) == "WEBP"sv) return true;
  return decoded_only_from_files(b);  // PFM, HDR, EXR
}

/// For the uncompressed formats whose header OpenCV trusts (PNM P1-P7, PFM): the bytes the header's
/// size needs, or 0 when the header cannot be read (OpenCV then rejects it). OpenCV allocates the
/// whole image from the header before reading its data: a 30-byte P6 header claiming 244604 x 4024
/// pixels asked for 2.9 GB (fuzzing finding 33). A PNM in text (P1-P3) needs at least one byte per
/// sample.
inline unsigned long long uncompressed_bytes_needed(std::string_view b, std::size_t& header_end) {
  if (b.size() < 3 || b[0] != 'P') return 0;
  const char kind = b[1];
  std::size_t i = 2;
  const auto token = [&]() -> std::string_view {
    while (i < b.size()) {  // whitespace and # comments
      if (b[i] == '#')
        while (i < b.size() && b[i] != '\n') ++i;
      else if (b[i] == ' ' || b[i] == '\t' || b[i] == '\n' || b[i] == '\r' || b[i] == '\v' || b[i] == '\f')
        ++i;
      else
        break;
    }
    const std::size_t start = i;
    while (i < b.size() && !(b[i] == ' ' || b[i] == '\t' || b[i] == '\n' || b[i] == '\r' || b[i] == '\v' ||
                             b[i] == '\f' || b[i] == '#'))
      ++i;
    return b.substr(start, i - start);
  };
  // A number is the token's leading digits, as OpenCV reads it ("4024\x1e4" is 4024).
  const auto number = [](std::string_view t) -> unsigned long long {
    unsigned long long v = 0;
    for (std::size_t k = 0; k < t.size() && k < 12 && t[k] >= '0' && t[k] <= '9'; ++k)
      v = v * 10 + unsigned(t[k] - '0');
    return v;
  };
  unsigned long long w = 0, h = 0, channels = 1, sample_bytes = 1;
  bool text = false;
  if (kind >= '1' && kind <= '6') {
    w = number(token()), h = number(token());
    if (kind != '1' && kind != '4') sample_bytes = number(token()) > 255 ? 2 : 1;
    channels = kind == '3' || kind == '6' ? 3 : 1;
    text = kind <= '3';
    if (kind == '4') sample_bytes = 0;  // bits: (w + 7) / 8 bytes a row
  } else if (kind == '7') {             // PAM: KEY value lines up to ENDHDR
    for (std::string_view t = token(); !t.empty() && t != "ENDHDR"; t = token()) {
      if (t == "WIDTH") w = number(token());
      if (t == "HEIGHT") h = number(token());
      if (t == "DEPTH") channels = number(token());
      if (t == "MAXVAL") sample_bytes = number(token()) > 255 ? 2 : 1;
    }
  } else if (kind == 'f' || kind == 'F') {
    w = number(token()), h = number(token());
    token();  // scale
    channels = kind == 'F' ? 3 : 1;
    sample_bytes = 4;
  } else {
    return 0;
  }
  if (w == 0 || h == 0 || channels == 0 || w > (1u << 20) || h > (1u << 20) || channels > 4) return 0;
  header_end = std::min(b.size(), i + 1);
  if (text) return w * h * channels;
  if (sample_bytes == 0) return (w + 7) / 8 * h;
  return w * h * channels * sample_bytes;
}

/// The decoded image (cv::IMREAD_* `flags`), or an empty Mat when the file is damaged (an OpenCV
/// assertion on a broken header counts as damaged); throws Error(path, ...) as read_image_file,
/// and for content that is not one of the formats above.
inline cv::Mat decode_image_file(const std::filesystem::path& path, int flags) {
  const std::string bytes = read_image_file(path);
  if (!supported_image_signature(bytes))
    throw Error(path.string(),
                "cannot decode: not an image format cropsight reads (PNG, JPEG, BMP, TIFF, PNM, PFM, WebP, HDR, EXR)");
  std::size_t header_end = 0;
  if (const unsigned long long need = uncompressed_bytes_needed(bytes, header_end);
      need > 0 && bytes.size() - header_end < need)
    throw Error(path.string(), "truncated image: its header needs " + std::to_string(need) +
                                   " bytes of pixels, the file has " + std::to_string(bytes.size() - header_end));
  try {
    if (decoded_only_from_files(bytes)) return cv::imread(path.string(), flags);
    return cv::imdecode(cv::Mat(1, int(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data())), flags);
  } catch (const cv::Exception&) {
    return {};
  }
}

}  // namespace cropsight::io
