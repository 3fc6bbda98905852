// The orientation step (paper Table 4.3; target <= 5 ms per potato) for each
// segmentation x axis x input on one shared shot (rgb/45_low_rgb/image8.png and its colourised
// depth image9.png, box from BoardBlobDetector as in the evaluation), or on a synthetic potato
// (brown ellipse on a white board, and its jet-coloured depth) when ../shared/data is absent.
// OpenCV runs single-threaded (cv::setNumThreads(0)). The number to compare across machines is
// the ratio of each benchmark to BM_Orientation/canny/pca/<same input> (the paper's fast method)
// in the same run: `build/bin/bench_potato_orientation`.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <opencv2/core.hpp>
#include <string>

#include "cropsight/io/image_io.hpp"
#include "cropsight/measure/orientation.hpp"
#include "cropsight/pipeline/potato/orientation_dataset.hpp"

using namespace cropsight;
using measure::OrientationAxis;
using measure::OrientationInput;
using measure::OrientationSegmentation;

namespace {

struct Shot {
  ColorImage rgb, depth;
  Detection2D box;
  std::string source;
};

// A 300 x 240 board with a 110 x 66 px potato at 30 degrees: RGB and jet depth (near = red).
Shot synthetic_shot() {
  Shot s{ColorImage(300, 240), ColorImage(300, 240), {}, "synthetic potato (no ../shared/data)"};
  const double t = 30 * std::numbers::pi / 180, a = 55, b = 33;
  for (int v = 0; v < 240; ++v)
    for (int u = 0; u < 300; ++u) {
      const double x = u + 0.5 - 150, y = -(v + 0.5 - 120);
      const double p = x * std::cos(t) + y * std::sin(t), q = -x * std::sin(t) + y * std::cos(t);
      const bool in = p * p / (a * a) + q * q / (b * b) <= 1;
      s.rgb.at(u, v) = in ? Rgb8{185, 140, 80} : Rgb8{235, 233, 228};
      s.depth.at(u, v) = in ? Rgb8{230, 20, 0} : Rgb8{0, 120, 255};
    }
  s.box = {92, 80, 208, 160, 0, 1};
  return s;
}

const Shot& shot() {
  static const Shot s = [] {
    const std::filesystem::path dir = std::filesystem::path(CROPSIGHT_SHARED_DATA_DIR) / "potato/orientation";
    const auto rgb = dir / "rgb/45_low_rgb/image8.png", depth = dir / "depth/45_low_depth/image9.png";
    if (!std::filesystem::exists(rgb) || !std::filesystem::exists(depth)) return synthetic_shot();
    Shot out{io::read_color(rgb), io::read_color(depth), {}, "shared shot 45_low image8/9"};
    pipeline::potato::BoardBlobDetector det;
    const auto boxes = det.detect({&out.rgb, nullptr});
    if (boxes.empty()) return synthetic_shot();
    out.box = boxes.front();
    return out;
  }();
  return s;
}

void BM_Orientation(benchmark::State& state, OrientationSegmentation seg, OrientationAxis axis, OrientationInput in) {
  cv::setNumThreads(0);
  const Shot& s = shot();
  measure::OrientationConfig cfg;
  cfg.segmentation = seg;
  cfg.axis = axis;
  cfg.input = in;
  const ColorImage& image = in == OrientationInput::depth ? s.depth : s.rgb;
  double angle = 0;
  for (auto _ : state) {
    const auto r = measure::estimate_orientation(image, s.box, cfg);
    angle = r.angle_rad;
    benchmark::DoNotOptimize(r.mask.data.data());
  }
  state.counters["angle_deg"] = angle * 180 / std::numbers::pi;
  state.SetLabel(s.source);
}

using S = OrientationSegmentation;
using A = OrientationAxis;
using I = OrientationInput;
// Canny + PCA first on each input: the baseline of the ratios.
BENCHMARK_CAPTURE(BM_Orientation, canny / pca / depth, S::canny, A::pca, I::depth)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Orientation, canny / ellipse / depth, S::canny, A::ellipse, I::depth)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Orientation, kmeans / pca / depth, S::kmeans, A::pca, I::depth)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Orientation, kmeans / ellipse / depth, S::kmeans, A::ellipse, I::depth)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Orientation, ours / pca / depth, S::ours, A::pca, I::depth)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Orientation, ours / ellipse / depth, S::ours, A::ellipse, I::depth)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Orientation, canny / pca / rgb, S::canny, A::pca, I::rgb)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Orientation, canny / ellipse / rgb, S::canny, A::ellipse, I::rgb)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Orientation, kmeans / pca / rgb, S::kmeans, A::pca, I::rgb)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Orientation, kmeans / ellipse / rgb, S::kmeans, A::ellipse, I::rgb)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Orientation, ours / pca / rgb, S::ours, A::pca, I::rgb)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Orientation, ours / ellipse / rgb, S::ours, A::ellipse, I::rgb)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
