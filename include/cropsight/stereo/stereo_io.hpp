#pragma once
// Image files for the stereo tools (PNG/PGM/JPEG through OpenCV). Throw Error(path, ...) when a
// file is missing or unreadable.
#include <filesystem>

#include "cropsight/core/image.hpp"
#include "cropsight/stereo/disparity.hpp"

namespace cropsight::stereo {

ColorImage read_color(const std::filesystem::path& path);  ///< any 8-bit image, converted to RGB
GrayImage read_gray(const std::filesystem::path& path);    ///< any 8-bit image, converted to grey
/// 8- or 16-bit single-channel ground-truth disparity divided by `scale`; stored 0 → NaN.
DisparityImage read_disparity(const std::filesystem::path& path, double scale);
/// 16-bit PNG with value = round(disparity * scale), 0 = no estimate (atomic write).
void write_disparity_png(const std::filesystem::path& path, const DisparityImage& disparity, double scale = 256.0);
/// 8-bit RGB PNG (atomic write).
void write_color_png(const std::filesystem::path& path, const ColorImage& image);
/// 8-bit single-channel PNG (atomic write).
void write_gray_png(const std::filesystem::path& path, const GrayImage& image);

}  // namespace cropsight::stereo
