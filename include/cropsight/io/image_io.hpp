#pragma once
// PNG and other images through OpenCV, with validation and atomic writes.
//
// Readers load with cv::IMREAD_UNCHANGED (never let OpenCV convert silently) and check the bit
// depth and channel count, so an 8-bit depth map or a colour label image is an error naming the
// file, not a silently wrong frame. Writers encode in memory with fixed PNG parameters (so equal
// images give byte-identical files, which the simulator's determinism relies on) and write
// atomically (temporary name, then rename). The format follows the extension (.png unless noted).
#include <filesystem>
#include <string>

#include "cropsight/core/image.hpp"

namespace cropsight::io {

/// An image file's bytes, checked before any decoder sees them: Error(path, ...) when it is
/// missing, a directory, unreadable or empty, or a PNG whose chunk list is cut short (libpng
/// prints its own "libpng error" line on stderr for a truncated file before OpenCV returns an
/// empty image, which broke the one-line error contract). Decode with cv::imdecode.
std::string read_image_file(const std::filesystem::path& path);

/// 16-bit single-channel PNG; throws Error(path, ...) on other bit depths/channels.
Image<std::uint16_t> read_u16(const std::filesystem::path& path);
/// 8-bit colour (3 channels; grey is expanded); throws Error(path, ...) on 16-bit images or
/// other channel counts.
ColorImage read_color(const std::filesystem::path& path);
/// 8-bit single-channel image; throws Error(path, ...) otherwise.
GrayImage read_gray(const std::filesystem::path& path);
void write_u16(const std::filesystem::path& path, const Image<std::uint16_t>& img);
void write_color(const std::filesystem::path& path, const ColorImage& img);
void write_gray(const std::filesystem::path& path, const GrayImage& img);

/// PNG file bytes of an image (deterministic: fixed compression parameters); used for files and
/// for images embedded in HTML reports. Throws Error("png", ...) for an empty image.
std::string encode_png(const ColorImage& img);
std::string encode_png(const GrayImage& img);
std::string encode_png(const Image<std::uint16_t>& img);

}  // namespace cropsight::io
