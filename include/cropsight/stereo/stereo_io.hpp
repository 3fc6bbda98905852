#pragma once
// Image files for the stereo tools (PNG/PGM/JPEG through OpenCV). Throw Error(path, ...) when a
// file is missing or unreadable.
#include <filesystem>
#include <string>
#include <utility>

#include "cropsight/core/image.hpp"
#include "cropsight/stereo/disparity.hpp"

namespace cropsight::stereo {

/// Any 8-bit image (grey, colour, with alpha), converted to RGB. Error(path, ...) for a 16-bit or
/// float file: OpenCV would silently scale it to 8 bits and the matcher would see another image.
ColorImage read_color(const std::filesystem::path& path);
/// Any 8-bit image, converted to grey; Error(path, ...) for another depth (see read_color).
GrayImage read_gray(const std::filesystem::path& path);
/// Left and right images of a stereo pair as RGB: both 8-bit (read_color), both grey or both
/// colour (a grey and a colour view of one scene match on different intensities), and of the same
/// size, else Error naming the offending file (the right one for a mismatch).
std::pair<ColorImage, ColorImage> read_color_pair(const std::filesystem::path& left,
                                                  const std::filesystem::path& right);
/// Single-channel ground-truth disparity divided by `scale`; stored 0 → NaN. `bits` = 8 or 16
/// requires that depth (Error(path, ...) otherwise: a 16-bit file read with an 8-bit scale is off
/// by 256x); 0 accepts either.
DisparityImage read_disparity(const std::filesystem::path& path, double scale, int bits = 0);
/// One-channel Portable Float Map ("Pf", the Middlebury 2014 ground-truth format): header "Pf",
/// "width height", scale (negative = little-endian), then rows of 32-bit floats from the bottom
/// row up. Values are returned as stored; infinite or NaN values (unknown in Middlebury) → NaN.
/// Throws Error(path, ...) for a missing file, a bad or colour ("PF") header, a size outside
/// 1..65535 or data shorter than width x height floats.
Image<float> read_pfm(const std::filesystem::path& path);
/// Ground-truth disparity of any of the formats the data sets use: .pfm (read_pfm), else an 8- or
/// 16-bit one-channel image (read_disparity, bits = 0); the stored value is divided by `scale`
/// and 0, infinite and NaN values become NaN (no ground truth). Throws Error(path, ...).
DisparityImage read_ground_truth(const std::filesystem::path& path, double scale);
/// Writes `values` as a little-endian one-channel PFM (tests, fixtures); atomic.
void write_pfm(const std::filesystem::path& path, const Image<float>& values);
/// Checks, before any work is done, that `path` can take an image written by the functions below:
/// a file name (not a folder) whose extension names a lossless format OpenCV can write (.png,
/// .tif, .tiff, .pgm, plus .bmp when !sixteen_bit); `option` (e.g. "--out") goes into the message.
/// Throws Error(path, ...).
void check_image_output(const std::filesystem::path& path, const std::string& option, bool sixteen_bit);
/// Disparity (px) as 16-bit values round(disparity x scale), 0 where there is none (NaN or <= 0);
/// what write_disparity_png stores.
DepthImage scaled_disparity(const DisparityImage& disparity, double scale = 256.0);
/// 16-bit PNG with value = round(disparity * scale), 0 = no estimate (atomic write).
void write_disparity_png(const std::filesystem::path& path, const DisparityImage& disparity, double scale = 256.0);
/// 8-bit RGB PNG (atomic write).
void write_color_png(const std::filesystem::path& path, const ColorImage& image);
/// 8-bit single-channel PNG (atomic write).
void write_gray_png(const std::filesystem::path& path, const GrayImage& image);

}  // namespace cropsight::stereo
