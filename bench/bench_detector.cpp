// The project's CenterNet detector on one 1280x720 grape image of the shared data
// (../shared/data/grape/coco_train/JPEGImages, the first by name), shipped weights:
//   BM_GrapeDetectorOnnx    nn::CenterNetOnnx::detect(): letterbox, OpenCV DNN forward of
//                           models/detector-grape.onnx, decoding: the path a robot without
//                           libtorch runs, and the one the target (<= 100 ms per
//                           1280x720 image on two cores) is about
//   BM_GrapeDetectorTorch   nn::CenterNet::detect() of models/detector-grape.pt (the same
//                           weights) through the libtorch plugin: the baseline in the same process
//   BM_GrapeDetectorOnnxMasks  boxes and per-class masks through OpenCV DNN: CenterNetOnnx::heads()
//                           (the main input and every mask_inputs pass, flip test as the model
//                           says), boxes_from_heads() and masks_from_heads() at 1280x720: what the
//                           grape paper's Table 2 comparison needs from each image
//   BM_GrapeDetectorTorchMasks  the same through the libtorch plugin (CenterNet::heads())
//   ...MasksInBoxes         the same two with masks_in_boxes(): each class's mask computed only
//                           inside its boxes
//   BM_GrapeDetectorMaskDecode  the mask decoding alone on heads computed once (every pixel / 0,
//                           inside the boxes / 1)
//   BM_GrapeDetectorBlob    the letterboxed input blob alone (nn::center_blob), the fixed cost
// Both detectors run on two threads (cv::setNumThreads(2); the plugin's threads = 2). The ratio
// of the ONNX row to the libtorch row of the same run is the number to compare across machines.
// CPU is the whole process's (every thread's) CPU time per iteration.
//
// CROPSIGHT_BENCH_DETECTOR=FILE.onnx replaces models/detector-grape.onnx in the ONNX rows (to time
// a candidate before it ships).
//
//   build/bin/bench_detector [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <opencv2/core/utility.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cropsight/core/install_paths.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/nn/center_decode.hpp"
#include "cropsight/nn/center_net.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "grape_bench_image.hpp"
#include "nn/center_codec.hpp"

namespace {
namespace fs = std::filesystem;
using namespace cropsight;

const fs::path kModels = cropsight::data_dir() / "models";  // the build tree mirrors an install

fs::path onnx_model() {
  const char* env = std::getenv("CROPSIGHT_BENCH_DETECTOR");
  return env != nullptr && *env != 0 ? fs::path(env) : kModels / "detector-grape.onnx";
}

using cropsight::bench::grape_image;

void BM_GrapeDetectorTorch(benchmark::State& state) {
  const fs::path m = kModels / "detector-grape.pt";
  if (!grape_image() || !fs::exists(m))
    return state.SkipWithError("needs ../shared/data/grape and models/detector-grape.pt");
  const nn::CenterNet net = nn::CenterNet::load(m, 2);
  // Untimed first calls: libtorch's executor profiles and optimises the graph on them, which a
  // short run (make bench: 0.3 s a benchmark) would otherwise time.
  for (int i = 0; i < 2; ++i) net.detect(*grape_image());
  std::size_t boxes = 0;
  for (auto _ : state) boxes = net.detect(*grape_image()).size();
  state.counters["boxes"] = double(boxes);
  state.SetLabel(std::to_string(grape_image()->width) + "x" + std::to_string(grape_image()->height));
}
BENCHMARK(BM_GrapeDetectorTorch)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

void BM_GrapeDetectorOnnx(benchmark::State& state) {
  const fs::path m = onnx_model();
  if (!grape_image() || !fs::exists(m))
    return state.SkipWithError("needs ../shared/data/grape and models/detector-grape.onnx");
  nn::CenterNetOnnx net(m);
  net.detect(*grape_image());  // untimed first call, as the libtorch one's
  std::size_t boxes = 0;
  for (auto _ : state) boxes = net.detect(*grape_image()).size();
  state.counters["boxes"] = double(boxes);
}
BENCHMARK(BM_GrapeDetectorOnnx)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

// Boxes and masks of one image from `heads_of` (either backend's heads()): the boxes decoded,
// then the masks over the whole image (masks_from_heads) or inside the boxes (masks_in_boxes).
template <class HeadsOf>
void boxes_and_masks(benchmark::State& state, const nn::CenterNetConfig& cfg, HeadsOf&& heads_of, bool in_boxes) {
  const ColorImage& image = *grape_image();
  std::size_t pixels = 0;
  for (auto _ : state) {
    const nn::CenterNetHeads h = heads_of(image);
    const auto boxes = nn::boxes_from_heads(h, cfg, image.width, image.height);
    const auto masks = in_boxes ? nn::masks_in_boxes(h, cfg, boxes, image.width, image.height)
                                : nn::masks_from_heads(h, cfg, image.width, image.height);
    pixels = 0;
    for (const auto& k : masks)
      pixels += std::size_t(std::count_if(k.data.begin(), k.data.end(), [](auto v) { return v != 0; }));
  }
  state.counters["mask_pixels"] = double(pixels);
  state.SetLabel(cfg.mask_inputs.empty() ? "one input" : "masks also at " + cfg.mask_inputs);
}

void onnx_masks(benchmark::State& state, bool in_boxes) {
  const fs::path m = onnx_model();
  if (!grape_image() || !fs::exists(m))
    return state.SkipWithError("needs ../shared/data/grape and models/detector-grape.onnx");
  nn::CenterNetOnnx net(m);
  boxes_and_masks(
      state, net.config(), [&](const ColorImage& im) { return net.heads(im); }, in_boxes);
}

void torch_masks(benchmark::State& state, bool in_boxes) {
  const fs::path m = kModels / "detector-grape.pt";
  if (!grape_image() || !fs::exists(m))
    return state.SkipWithError("needs ../shared/data/grape and models/detector-grape.pt");
  const nn::CenterNet net = nn::CenterNet::load(m, 2);
  for (int i = 0; i < 2; ++i) net.heads(*grape_image());  // untimed: libtorch's first calls
  boxes_and_masks(
      state, net.config(), [&](const ColorImage& im) { return net.heads(im); }, in_boxes);
}

void BM_GrapeDetectorOnnxMasks(benchmark::State& state) { onnx_masks(state, false); }
BENCHMARK(BM_GrapeDetectorOnnxMasks)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
void BM_GrapeDetectorOnnxMasksInBoxes(benchmark::State& state) { onnx_masks(state, true); }
BENCHMARK(BM_GrapeDetectorOnnxMasksInBoxes)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
void BM_GrapeDetectorTorchMasks(benchmark::State& state) { torch_masks(state, false); }
BENCHMARK(BM_GrapeDetectorTorchMasks)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
void BM_GrapeDetectorTorchMasksInBoxes(benchmark::State& state) { torch_masks(state, true); }
BENCHMARK(BM_GrapeDetectorTorchMasksInBoxes)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

// The mask decoding alone, on heads computed once: arg 0 every pixel, 1 inside the boxes.
void BM_GrapeDetectorMaskDecode(benchmark::State& state) {
  const fs::path m = onnx_model();
  if (!grape_image() || !fs::exists(m))
    return state.SkipWithError("needs ../shared/data/grape and models/detector-grape.onnx");
  nn::CenterNetOnnx net(m);
  const nn::CenterNetConfig& cfg = net.config();
  const ColorImage& image = *grape_image();
  const nn::CenterNetHeads h = net.heads(image);
  const auto boxes = nn::boxes_from_heads(h, cfg, image.width, image.height);
  for (auto _ : state)
    benchmark::DoNotOptimize(state.range(0) ? nn::masks_in_boxes(h, cfg, boxes, image.width, image.height)
                                            : nn::masks_from_heads(h, cfg, image.width, image.height));
  state.SetLabel(state.range(0) ? "inside the boxes" : "every pixel");
}
BENCHMARK(BM_GrapeDetectorMaskDecode)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

void BM_GrapeDetectorBlob(benchmark::State& state) {
  const fs::path m = onnx_model();
  if (!grape_image() || !fs::exists(m))
    return state.SkipWithError("needs ../shared/data/grape and models/detector-grape.onnx");
  const nn::CenterNetConfig cfg = nn::CenterNetOnnx(m).config();
  for (auto _ : state)
    benchmark::DoNotOptimize(nn::center_blob(*grape_image(), cfg.input_width, cfg.input_height, nullptr));
}
BENCHMARK(BM_GrapeDetectorBlob)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  cv::setNumThreads(2);  // the two cores
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
