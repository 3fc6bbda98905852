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

namespace {
bool is_image_name(const fs::path& p) {
  const std::string ext = lower_extension(p);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}
}  // namespace

std::vector<fs::path> list_images(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_regular_file(dir, ec) && is_image_name(dir)) return {dir};
  if (!fs::is_directory(dir, ec)) throw Error(dir.string(), "no such image or folder of images");
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && is_image_name(e.path())) out.push_back(e.path());
  if (out.empty()) throw Error(dir.string(), "holds no .jpg or .png image");
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace cropsight::io
