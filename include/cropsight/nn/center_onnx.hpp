#pragma once
// nn::CenterNet as an ONNX file, run by OpenCV's DNN module (no libtorch at run time: the
// robot's path). CenterNet::export_onnx writes the graph; CenterNetOnnx runs it.
//
// The graph (opset 11): input "images" float [1, 3, H, W] (RGB / 255, letterboxed as in
// center_net.hpp), outputs "heatmap" [1, C, H/4, W/4] (sigmoid), "size" and "offset"
// [1, 2, H/4, W/4], "mask" [1, C, H/4, W/4] (sigmoid). Operators: Conv (BatchNorm folded in),
// Relu, Add, Resize (nearest, scales 2, asymmetric / floor), Sigmoid: all of them OpenCV 4.6
// loads. The model's metadata (metadata_props "cropsight.*": kind, class names, input size,
// score threshold, top K) travels in the file, so the file alone is the detector.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/nn/center_net.hpp"

namespace cropsight::nn {

class CenterNetOnnx final : public Detector2D {
 public:
  /// Loads `path` and checks its metadata and its four outputs on one blank input. Throws
  /// Error(path, ...) for a missing file, one that is not ONNX, one without the detector's
  /// metadata, or outputs of a foreign layout.
  explicit CenterNetOnnx(const std::filesystem::path& path);
  ~CenterNetOnnx() override;
  CenterNetOnnx(const CenterNetOnnx&) = delete;
  CenterNetOnnx& operator=(const CenterNetOnnx&) = delete;

  /// The configuration the file was exported with (training fields as saved).
  const CenterNetConfig& config() const;
  CenterNetHeads heads(const ColorImage& image);
  std::vector<Detection2D> detect(const ColorImage& image);
  std::vector<Detection2D> detect(const DetectorInput& in) override;
  std::vector<std::string> class_names() const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A detector for `path` by its extension: .onnx → CenterNetOnnx, else a libtorch model
/// (CenterNet::load with `threads`).
std::unique_ptr<Detector2D> load_center_detector(const std::filesystem::path& path, int threads = 1);

/// The configuration of a CenterNet or CenterNetOnnx (as load_center_detector returns). Throws
/// Error(where) for another kind of Detector2D.
const CenterNetConfig& center_net_config(const Detector2D& detector, const std::string& where);

}  // namespace cropsight::nn
