#pragma once
// The one way the library decodes an image file with OpenCV (io, stereo): the bytes come from
// io::read_image_file (which names a missing, folder, empty or truncated file first), then
// cv::imdecode. Internal header: OpenCV stays out of the public ones.
#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <string>
#include <string_view>

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

/// The decoded image (cv::IMREAD_* `flags`), or an empty Mat when the file is damaged (an OpenCV
/// assertion on a broken header counts as damaged); throws Error(path, ...) as read_image_file.
inline cv::Mat decode_image_file(const std::filesystem::path& path, int flags) {
  const std::string bytes = read_image_file(path);
  try {
    if (decoded_only_from_files(bytes)) return cv::imread(path.string(), flags);
    return cv::imdecode(cv::Mat(1, int(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data())), flags);
  } catch (const cv::Exception&) {
    return {};
  }
}

}  // namespace cropsight::io
