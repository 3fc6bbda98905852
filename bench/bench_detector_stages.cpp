// Where the grape detector's time goes, stage by stage, on the image and weights of
// bench_detector.cpp (../shared/data/grape/coco_train/JPEGImages, the first by name; the shipped
// models/detector-grape.{onnx,pt}, 640x352 input, flip test on):
//   BM_DetectorStageOnnxForward   one OpenCV DNN forward pass of the letterboxed blob, all four
//                                 heads; counters: the ms of each group of layers by OpenCV's own
//                                 per-layer timer (Net::getPerfProfile): backbone (s0a..s4b), FPN
//                                 (laterals, upsampling, sums, smoothing), box heads (heatmap,
//                                 size, offset), mask head
//   BM_DetectorStageTorchForward  one libtorch forward of one blob (arg 1) or of the blob and its
//                                 mirror (arg 2: the flip test's batch, one thread per image)
//   BM_DetectorStageFlip          mirrored_blob() and merge_mirrored_heads(): the flip test's own work
//   BM_DetectorStageDecode        boxes_from_heads(): peaks, top K, letterbox back (no NMS)
// The letterboxed blob (BM_GrapeDetectorBlob) and the mask decoding (BM_GrapeDetectorMaskDecode)
// are timed in bench_detector.cpp. CPU is the whole process's.
//
//   build/bin/bench_detector_stages
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <opencv2/core/utility.hpp>
#include <opencv2/dnn.hpp>
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

namespace detector_stages {
namespace fs = std::filesystem;
using namespace cropsight;

const fs::path kModel = cropsight::data_dir() / "models" / "detector-grape";

using cropsight::bench::grape_image;

// The group of a layer of the exported graph by its name (center_onnx_writer.cpp names them;
// OpenCV's importer prefixes "onnx_node!").
std::string layer_group(std::string name) {
  if (name.rfind("onnx_node!", 0) == 0) name = name.substr(10);
  if (name.size() > 1 && name[0] == 's' && std::isdigit(static_cast<unsigned char>(name[1]))) return "backbone";
  for (const char* head : {"hm.", "wh.", "off.", "heatmap", "size", "offset"})
    if (name.rfind(head, 0) == 0) return "box_heads";
  if (name.rfind("seg.", 0) == 0 || name == "mask") return "mask_head";
  return "fpn";
}

void BM_DetectorStageOnnxForward(benchmark::State& state) {
  if (!grape_image() || !fs::exists(kModel.string() + ".onnx"))
    return state.SkipWithError("needs ../shared/data/grape and models/detector-grape.onnx");
  const nn::CenterNetConfig cfg = nn::CenterNetOnnx(kModel.string() + ".onnx").config();
  cv::dnn::Net net = cv::dnn::readNetFromONNX(kModel.string() + ".onnx");
  const std::vector<float> blob = nn::center_blob(*grape_image(), cfg.input_width, cfg.input_height, nullptr);
  const int dims[4] = {1, 3, cfg.input_height, cfg.input_width};
  const std::vector<std::string> outputs = {"heatmap", "size", "offset", "mask"};
  std::vector<cv::Mat> outs;
  std::map<std::string, double> ms;
  const std::vector<std::string> names = net.getLayerNames();
  for (auto _ : state) {
    net.setInput(cv::Mat(4, dims, CV_32F, const_cast<float*>(blob.data())));
    net.forward(outs, outputs);
    std::vector<double> per_layer;
    net.getPerfProfile(per_layer);
    for (std::size_t i = 0; i < per_layer.size() && i < names.size(); ++i)
      ms[layer_group(names[i])] += per_layer[i] * 1000.0 / cv::getTickFrequency();
  }
  for (const auto& [group, total] : ms) state.counters[group + "_ms"] = total / double(state.iterations());
}
BENCHMARK(BM_DetectorStageOnnxForward)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

void BM_DetectorStageTorchForward(benchmark::State& state) {
  if (!grape_image() || !fs::exists(kModel.string() + ".pt"))
    return state.SkipWithError("needs ../shared/data/grape and models/detector-grape.pt");
  nn::CenterNet net = nn::CenterNet::load(kModel.string() + ".pt", 2);
  net.set_flip_test(state.range(0) == 2);
  for (int i = 0; i < 2; ++i) net.heads(*grape_image());  // untimed: libtorch's first calls
  for (auto _ : state) benchmark::DoNotOptimize(net.heads(*grape_image()));
  state.SetLabel(state.range(0) == 2 ? "blob and mirror (flip test), blob included" : "one blob, blob included");
}
BENCHMARK(BM_DetectorStageTorchForward)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

void BM_DetectorStageFlip(benchmark::State& state) {
  if (!grape_image() || !fs::exists(kModel.string() + ".onnx"))
    return state.SkipWithError("needs ../shared/data/grape and models/detector-grape.onnx");
  nn::CenterNetOnnx net(kModel.string() + ".onnx");
  const nn::CenterNetConfig& cfg = net.config();
  const nn::CenterNetHeads heads = net.heads(*grape_image());
  const std::vector<float> blob = nn::center_blob(*grape_image(), cfg.input_width, cfg.input_height, nullptr);
  for (auto _ : state) {
    benchmark::DoNotOptimize(nn::mirrored_blob(blob, cfg.input_width, cfg.input_height));
    nn::CenterNetHeads h = heads;
    nn::merge_mirrored_heads(h, heads);
    benchmark::DoNotOptimize(h.mask.data());
  }
}
BENCHMARK(BM_DetectorStageFlip)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

void BM_DetectorStageDecode(benchmark::State& state) {
  if (!grape_image() || !fs::exists(kModel.string() + ".onnx"))
    return state.SkipWithError("needs ../shared/data/grape and models/detector-grape.onnx");
  nn::CenterNetOnnx net(kModel.string() + ".onnx");
  const nn::CenterNetHeads heads = net.heads(*grape_image());
  for (auto _ : state)
    benchmark::DoNotOptimize(nn::boxes_from_heads(heads, net.config(), grape_image()->width, grape_image()->height));
}
BENCHMARK(BM_DetectorStageDecode)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

}  // namespace detector_stages

int main(int argc, char** argv) {
  cv::setNumThreads(2);  // the two cores of the speed targets, as bench_detector
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
