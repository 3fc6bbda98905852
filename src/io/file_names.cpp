#include "cropsight/io/file_names.hpp"

#include <algorithm>
#include <cctype>

#include "cropsight/core/error.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::vector<fs::path> list_files_with(const fs::path& dir, const std::vector<std::string>& extensions,
                                      const std::string& what) {
  const auto wanted = [&](const fs::path& p) {
    return std::find(extensions.begin(), extensions.end(), lower_extension(p)) != extensions.end();
  };
  std::error_code ec;
  if (fs::is_regular_file(dir, ec) && wanted(dir)) return {dir};
  if (!fs::is_directory(dir, ec)) throw Error(dir.string(), "no such " + what + " or folder of them");
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && wanted(e.path())) out.push_back(e.path());
  if (out.empty()) throw Error(dir.string(), "holds no " + what);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<fs::path> list_images(const fs::path& dir) {
  return list_files_with(dir, {".png", ".jpg", ".jpeg"}, ".jpg or .png image");
}

}  // namespace cropsight::io
