// The classical potato detector on one shared 416x416 image (target: <= 5 ms per image
// on one core), next to a baseline that every colour-threshold detector pays: cv::cvtColor to
// Lab plus one cv::threshold. OpenCV runs single-threaded here (cv::setNumThreads(0)), so the
// figures are one core's. The ratio BM_PotatoBlobDetector / BM_CvtColorThreshold is the number
// to compare across machines. BM_PotatoBlobDetectorAllShared runs all 11 shared images per
// iteration (divide by 11 for one image).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "cropsight/io/image_io.hpp"
#include "cropsight/pipeline/potato/blob_detector.hpp"

using namespace cropsight;

namespace {

// The shared detection images, sorted by name; empty when the data is absent.
const std::vector<ColorImage>& shared_images() {
  static const std::vector<ColorImage> images = [] {
    const std::filesystem::path dir = std::filesystem::path(CROPSIGHT_SHARED_DATA_DIR) / "potato/detection/images";
    std::vector<std::filesystem::path> files;
    if (std::filesystem::is_directory(dir))
      for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    std::vector<ColorImage> out;
    for (const auto& f : files) out.push_back(io::read_color(f));
    return out;
  }();
  return images;
}

// The first image (by name): no touching potatoes, so no split search.
const ColorImage& shared_image() {
  static const ColorImage none;
  return shared_images().empty() ? none : shared_images().front();
}

void BM_CvtColorThreshold(benchmark::State& state) {
  cv::setNumThreads(0);
  const ColorImage& img = shared_image();
  if (img.empty()) return state.SkipWithError("shared potato images not found");
  const cv::Mat rgb(img.height, img.width, CV_8UC3, const_cast<Rgb8*>(img.data.data()));
  cv::Mat lab, b, mask;
  for (auto _ : state) {
    cv::cvtColor(rgb, lab, cv::COLOR_RGB2Lab);
    cv::extractChannel(lab, b, 2);
    cv::threshold(b, mask, 140, 255, cv::THRESH_BINARY);
    benchmark::DoNotOptimize(mask.data);
  }
}
BENCHMARK(BM_CvtColorThreshold)->Unit(benchmark::kMillisecond);

void BM_PotatoBlobDetector(benchmark::State& state) {
  cv::setNumThreads(0);
  const ColorImage& img = shared_image();
  if (img.empty()) return state.SkipWithError("shared potato images not found");
  pipeline::potato::BlobDetector det;
  std::size_t boxes = 0;
  for (auto _ : state) {
    const auto d = det.detect({&img, nullptr});
    boxes = d.size();
    benchmark::DoNotOptimize(d.data());
  }
  state.counters["boxes"] = double(boxes);
}
BENCHMARK(BM_PotatoBlobDetector)->Unit(benchmark::kMillisecond);

// All 11 shared images per iteration (the touching-potato splits and clutter included); the time
// per image is the iteration time / 11.
void BM_PotatoBlobDetectorAllShared(benchmark::State& state) {
  cv::setNumThreads(0);
  const std::vector<ColorImage>& images = shared_images();
  if (images.empty()) return state.SkipWithError("shared potato images not found");
  pipeline::potato::BlobDetector det;
  for (auto _ : state)
    for (const ColorImage& img : images) {
      const auto d = det.detect({&img, nullptr});
      benchmark::DoNotOptimize(d.data());
    }
  state.counters["images"] = double(images.size());
}
BENCHMARK(BM_PotatoBlobDetectorAllShared)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
