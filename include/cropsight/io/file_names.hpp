#pragma once
// What a file's name says: its extension, and the images of a folder. One helper each, for every
// reader and command that chooses by extension.
#include <filesystem>
#include <string>
#include <vector>

namespace cropsight::io {

/// The extension of `path` in lower case with its dot (".png" for "A.PNG"); "" when it has none.
std::string lower_extension(const std::filesystem::path& path);

/// The regular files of folder `dir` whose lower-case extension is one of `extensions` (".ply",
/// with the dot), in name order, or `dir` itself when it is one such file. Throws Error(dir, ...)
/// naming `what` ("grape cloud") when it is neither, or a folder holding none.
std::vector<std::filesystem::path> list_files_with(const std::filesystem::path& dir,
                                                   const std::vector<std::string>& extensions, const std::string& what);

/// The images of folder `dir` (.png, .jpg, .jpeg, any case; regular files) in name order, or
/// `dir` itself when it is one image file. Throws Error(dir, ...) when it is neither, or a folder
/// holding no image.
std::vector<std::filesystem::path> list_images(const std::filesystem::path& dir);

}  // namespace cropsight::io
