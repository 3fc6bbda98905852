// libFuzzer harness: ONNX detector files, as `detect potato` (the `onnx` backend,
// YOLOv5, YOLOv8 and SSD layouts) and `detect objects` (the project's own CenterNet export, with its
// metadata) load them: OpenCV DNN's ONNX importer behind our checks, then, for a file that
// loads, one detection on a small image (the output decoding is ours).
#include <fuzzer/FuzzedDataProvider.h>

#include "cropsight/nn/center_onnx.hpp"
#include "cropsight/nn/onnx_detector.hpp"
#include "fuzz_support.hpp"

namespace {

void load_and_detect(const char* what, const std::function<std::unique_ptr<cropsight::Detector2D>()>& make) {
  cropsight::fuzz::expect_error_or_success(what, [&] {
    const auto detector = make();
    const cropsight::ColorImage image(40, 30, cropsight::Rgb8{90, 60, 30});
    cropsight::DetectorInput in;
    in.image = &image;
    (void)detector->detect(in);
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "model.onnx");
  for (const auto layout :
       {cropsight::nn::OnnxLayout::yolov5, cropsight::nn::OnnxLayout::yolov8, cropsight::nn::OnnxLayout::ssd}) {
    load_and_detect("OnnxDetector", [&] {
      cropsight::nn::OnnxDetectorConfig cfg;
      cfg.model = path.string();
      cfg.layout = layout;
      cfg.input_width = cfg.input_height = 64;  // the seeds' size (tests/nn/make_onnx_fixtures.py)
      return cropsight::nn::make_onnx_detector(cfg);
    });
  }
  load_and_detect("CenterNetOnnx", [&] { return std::make_unique<cropsight::nn::CenterNetOnnx>(path); });
  return 0;
}
