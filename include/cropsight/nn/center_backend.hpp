#pragma once
// Which runtime runs the project's CenterNet detector (center_net.hpp): the libtorch plugin on the
// .pt weights, or OpenCV DNN on the exported .onnx (center_onnx.hpp). The two give the same boxes
// and masks within float rounding (tests/nn/test_center_onnx.cpp); on the shared 2-core Intel
// Xeon VM libtorch runs the shipped grape model in about half OpenCV DNN's time
// (docs/pipelines/detector.md), so "auto" takes libtorch where the plugin is installed and falls
// back to OpenCV DNN where it is not (a robot built without libtorch).
#include <array>
#include <memory>
#include <string>

#include "cropsight/core/detection2d.hpp"

namespace cropsight::nn {

/// The runtime of a CenterNet model given by name: auto = libtorch when its plugin loads and the
/// model has .pt weights, else OpenCV DNN on the .onnx; libtorch or opencv = that one only.
enum class DetectorRuntime { automatic, libtorch, opencv };
constexpr std::array<const char*, 3> config_names(DetectorRuntime) { return {"auto", "libtorch", "opencv"}; }

/// Whether the libtorch plugin (libcropsight_nn_torch.so, point_segmenter.hpp says where it is
/// looked for) loads in this process. Loading it is the test, so a true answer has loaded libtorch.
bool libtorch_available();

/// The detector `model` names, run by `runtime`. `model` is a file (.pt or .onnx: its extension
/// picks the runtime, and one that contradicts an explicit `runtime` is an Error) or a shipped
/// model's name without extension (models/NAME.pt and models/NAME.onnx, io::find_model), which
/// `runtime` resolves: auto takes NAME.pt when libtorch_available(), else NAME.onnx. `threads`
/// are libtorch's (at::set_num_threads). Throws Error(model, ...) when no file fits.
std::unique_ptr<Detector2D> open_center_detector(const std::string& model, DetectorRuntime runtime, int threads);

}  // namespace cropsight::nn
