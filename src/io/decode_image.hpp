#pragma once
// The one way the library decodes an image file with OpenCV (io, stereo): the bytes come from
// io::read_image_file (which names a missing, folder, empty or truncated file first), then
// cv::imdecode. Internal header: OpenCV stays out of the public ones.
#include <opencv2/imgcodecs.hpp>

#include <filesystem>

#include "cropsight/io/image_io.hpp"

namespace cropsight::io {

/// The decoded image (cv::IMREAD_* `flags`), or an empty Mat when the file is damaged (an OpenCV
/// assertion on a broken header counts as damaged); throws Error(path, ...) as read_image_file.
inline cv::Mat decode_image_file(const std::filesystem::path& path, int flags) {
  const std::string bytes = read_image_file(path);
  try {
    return cv::imdecode(cv::Mat(1, int(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data())), flags);
  } catch (const cv::Exception&) {
    return {};
  }
}

}  // namespace cropsight::io
