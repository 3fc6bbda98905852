#pragma once
// The one way the library decodes an image file with OpenCV (io, stereo): the bytes come from
// io::read_image_file (which names a missing, folder, empty or truncated file first), then
// cv::imdecode. Internal header: OpenCV stays out of the public ones.
#include <opencv2/imgcodecs.hpp>

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

/// The decoded image (cv::IMREAD_* `flags`), or an empty Mat when the file is damaged (an OpenCV
/// assertion on a broken header counts as damaged); throws Error(path, ...) as read_image_file,
/// and for content that is not one of the formats above.
inline cv::Mat decode_image_file(const std::filesystem::path& path, int flags) {
  const std::string bytes = read_image_file(path);
  if (!supported_image_signature(bytes))
    throw Error(path.string(),
                "cannot decode: not an image format cropsight reads (PNG, JPEG, BMP, TIFF, PNM, PFM, WebP, HDR, EXR)");
  try {
    if (decoded_only_from_files(bytes)) return cv::imread(path.string(), flags);
    return cv::imdecode(cv::Mat(1, int(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data())), flags);
  } catch (const cv::Exception&) {
    return {};
  }
}

}  // namespace cropsight::io
