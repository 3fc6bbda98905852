// The ONNX detector's own cost (nn::OnnxDetector), apart from the user's network:
//   BM_DecodeNms/L   decode + per-class NMS of a YOLOv5 416 x 416 output, N = 6300 rows
//                    (3 x (52² + 26² + 13²)), one class; L = 0 yolov5 [1, N, 6], 1 yolov8
//                    [1, 5, N]. The rows are shaped like a real frame: objectness mostly near 0,
//                    five potatoes each claimed by 12 overlapping rows above the threshold.
//   BM_TinyForward   cv::dnn forward of tests/nn/make_onnx_fixtures.py's yolov5.onnx (64 x 64
//                    input, four layers) — OpenCV DNN's fixed cost per call; counter `ratio` =
//                    its time over that of blobFromImage on the same 64 x 64 canvas, measured in
//                    the same process (the number to compare across machines).
//   BM_DetectTiny    OnnxDetector::detect() of a 640 x 480 image through that graph: letterbox,
//                    blob, forward, decode, NMS.
// The fixtures are written with Debian's python3-onnx (/usr/bin/python3); without it the two
// graph benchmarks report an error and BM_DecodeNms still runs.
#include <benchmark/benchmark.h>

#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <opencv2/dnn.hpp>
#include <random>

#include "cropsight/core/timer.hpp"
#include "cropsight/nn/onnx_detector.hpp"
#include "nn/onnx_decode.hpp"

namespace {
using namespace cropsight;
using namespace cropsight::nn;

constexpr int kRows = 6300;

// A [N, 6] YOLOv5 table (cx, cy, w, h, objectness, class score) in 416 x 416 input pixels.
std::vector<float> yolov5_table(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<float> t(std::size_t(kRows) * 6);
  for (int i = 0; i < kRows; ++i) {
    float* p = &t[std::size_t(i) * 6];
    p[0] = 416 * u(rng), p[1] = 416 * u(rng), p[2] = 10 + 60 * u(rng), p[3] = 10 + 60 * u(rng);
    p[4] = 0.05f * u(rng), p[5] = u(rng);
  }
  for (int k = 0; k < 5; ++k)  // five potatoes, 12 rows each around their centre
    for (int j = 0; j < 12; ++j) {
      float* p = &t[std::size_t(k * 1000 + j * 7) * 6];
      p[0] = 60 + 70 * k + 4 * u(rng), p[1] = 200 + 4 * u(rng), p[2] = 50 + 4 * u(rng), p[3] = 40 + 4 * u(rng);
      p[4] = 0.5f + 0.5f * u(rng), p[5] = 0.9f;
    }
  return t;
}

void BM_DecodeNms(benchmark::State& state) {
  const bool v8 = state.range(0) == 1;
  std::vector<float> t = yolov5_table(1);
  if (v8) {  // [5, N]: channel-major, score = objectness x class
    std::vector<float> c(std::size_t(kRows) * 5);
    for (int i = 0; i < kRows; ++i) {
      for (int r = 0; r < 4; ++r) c[std::size_t(r) * kRows + i] = t[std::size_t(i) * 6 + r];
      c[std::size_t(4) * kRows + i] = t[std::size_t(i) * 6 + 4] * t[std::size_t(i) * 6 + 5];
    }
    t = std::move(c);
  }
  const Letterbox lb = Letterbox::fit(640, 480, 416, 416, OnnxResize::letterbox);
  std::size_t kept = 0, candidates = 0;
  for (auto _ : state) {
    const auto cand = v8 ? decode_rows(OnnxLayout::yolov8, t.data(), 5, kRows, lb, 0.25f)
                         : decode_rows(OnnxLayout::yolov5, t.data(), kRows, 6, lb, 0.25f);
    const auto boxes = nms_per_class(cand, 0.45f, 300);
    candidates = cand.size(), kept = boxes.size();
    benchmark::DoNotOptimize(boxes.data());
  }
  state.counters["candidates"] = double(candidates);
  state.counters["kept"] = double(kept);
}
BENCHMARK(BM_DecodeNms)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The fixtures, written once per process; "" when python3-onnx is missing.
const std::filesystem::path& fixtures() {
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::temp_directory_path() / ("cropsight-bench-onnx-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    const std::string cmd = "/usr/bin/python3 '" CROPSIGHT_SOURCE_DIR "/tests/nn/make_onnx_fixtures.py' '" +
                            d.string() + "' >/dev/null 2>&1";
    return std::system(cmd.c_str()) == 0 ? d : std::filesystem::path();
  }();
  return dir;
}

// Mean microseconds per call of f over `reps` calls.
template <class F>
double mean_us(int reps, F&& f) {
  Stopwatch w;
  for (int i = 0; i < reps; ++i) f();
  return 1000.0 * w.ms() / reps;
}

void BM_TinyForward(benchmark::State& state) {
  if (fixtures().empty()) return state.SkipWithError("python3-onnx missing: no fixture graphs");
  cv::dnn::Net net = cv::dnn::readNetFromONNX((fixtures() / "yolov5.onnx").string());
  const cv::Mat canvas(64, 64, CV_8UC3, cv::Scalar(114, 114, 114));
  cv::Mat blob = cv::dnn::blobFromImage(canvas, 1.0 / 255);
  const auto forward = [&] {
    net.setInput(blob);
    cv::Mat out = net.forward();
    benchmark::DoNotOptimize(out.data);
  };
  forward();  // the first call allocates
  for (auto _ : state) forward();
  const double baseline = mean_us(2000, [&] {
    cv::dnn::blobFromImage(canvas, blob, 1.0 / 255);
    benchmark::DoNotOptimize(blob.data);
  });
  state.counters["blob_us"] = baseline;
  state.counters["ratio"] = mean_us(2000, forward) / baseline;
}
BENCHMARK(BM_TinyForward)->Unit(benchmark::kMicrosecond);

void BM_DetectTiny(benchmark::State& state) {
  if (fixtures().empty()) return state.SkipWithError("python3-onnx missing: no fixture graphs");
  OnnxDetectorConfig c;
  c.model = (fixtures() / "yolov5.onnx").string();
  c.input_width = c.input_height = 64;
  c.class_names = "potato, sprout";
  OnnxDetector det(c);
  const ColorImage img(640, 480, Rgb8{90, 120, 60});
  std::size_t n = 0;
  for (auto _ : state) n = det.detect({&img, nullptr}).size();
  state.counters["boxes"] = double(n);
}
BENCHMARK(BM_DetectTiny)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
