#pragma once
// The one 1280x720 grape image the detector benchmarks time (bench_detector.cpp,
// bench_detector_stages.cpp): the first by name of ../shared/data/grape/coco_train/JPEGImages,
// read once; empty when the shared data is absent (the benchmarks then skip with a message).
#include <algorithm>
#include <filesystem>
#include <optional>
#include <vector>

#include "cropsight/core/image.hpp"
#include "cropsight/io/image_io.hpp"

namespace cropsight::bench {

inline const std::optional<ColorImage>& grape_image() {
  static const std::optional<ColorImage> image = []() -> std::optional<ColorImage> {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(CROPSIGHT_SHARED_DATA_DIR) / "grape" / "coco_train" / "JPEGImages";
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return std::nullopt;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().extension() == ".jpg" || e.path().extension() == ".png") files.push_back(e.path());
    if (files.empty()) return std::nullopt;
    return io::read_color(*std::min_element(files.begin(), files.end()));
  }();
  return image;
}

}  // namespace cropsight::bench
