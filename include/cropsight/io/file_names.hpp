#pragma once
// What a file's name says: its extension, and the images of a folder. One helper each, for every
// reader and command that chooses by extension.
#include <filesystem>
#include <string>
#include <vector>

namespace cropsight::io {

/// The extension of `path` in lower case with its dot (".png" for "A.PNG"); "" when it has none.
std::string lower_extension(const std::filesystem::path& path);

/// The images of folder `dir` (.png, .jpg, .jpeg, any case; regular files) in name order, or
/// `dir` itself when it is one image file. Throws Error(dir, ...) when it is neither, or a folder
/// holding no image.
std::vector<std::filesystem::path> list_images(const std::filesystem::path& dir);

}  // namespace cropsight::io
