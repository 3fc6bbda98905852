#pragma once
// PNG and other images through OpenCV, with validation and atomic writes.
#include <filesystem>

#include "cropsight/core/image.hpp"

namespace cropsight::io {

/// 16-bit single-channel PNG; throws Error(path, ...) on other bit depths/channels.
Image<std::uint16_t> read_u16(const std::filesystem::path& path);
/// 8-bit colour (3 channels; grey is expanded); throws Error(path, ...) on 16-bit images.
ColorImage read_color(const std::filesystem::path& path);
GrayImage read_gray(const std::filesystem::path& path);
void write_u16(const std::filesystem::path& path, const Image<std::uint16_t>& img);
void write_color(const std::filesystem::path& path, const ColorImage& img);
void write_gray(const std::filesystem::path& path, const GrayImage& img);

}  // namespace cropsight::io
