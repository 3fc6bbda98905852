// The runtime choice of the CenterNet detector (include/cropsight/nn/center_backend.hpp).
#include "cropsight/nn/center_backend.hpp"

#include <filesystem>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "nn/segmenter_backend.hpp"

namespace cropsight::nn {

bool libtorch_available() {
  try {
    detail::backend_api();
    return true;
  } catch (const Error&) {
    return false;
  }
}

namespace {
// models/NAME.ext (or NAME.ext as a path) when it is there; empty otherwise.
std::string shipped(const std::string& name, const char* ext) {
  try {
    return io::find_model(name + ext).string();
  } catch (const Error&) {
    return {};
  }
}
}  // namespace

std::unique_ptr<Detector2D> open_center_detector(const std::string& model, DetectorRuntime runtime, int threads) {
  namespace fs = std::filesystem;
  const std::string ext = fs::path(model).extension().string();
  std::error_code ec;
  if (ext == ".pt" || ext == ".onnx" || fs::is_regular_file(model, ec)) {
    // A file the user named: its extension is the runtime; asking for the other one is a mistake.
    const bool onnx_file = ext == ".onnx";
    if ((runtime == DetectorRuntime::libtorch && onnx_file) || (runtime == DetectorRuntime::opencv && !onnx_file))
      throw Error(model, "is a " + std::string(onnx_file ? ".onnx" : "libtorch") +
                             " model, but the detector runtime is " + config_name(runtime) +
                             " (libtorch runs .pt, opencv .onnx; auto follows the extension)");
    return load_center_detector(io::find_model(model), threads);
  }
  std::string file;
  if (runtime != DetectorRuntime::opencv && (runtime == DetectorRuntime::libtorch || libtorch_available()))
    file = shipped(model, ".pt");
  if (file.empty() && runtime != DetectorRuntime::libtorch) file = shipped(model, ".onnx");
  if (file.empty())
    throw Error(model, std::string("no such detector model (looked for ") +
                           (runtime == DetectorRuntime::opencv     ? "NAME.onnx"
                            : runtime == DetectorRuntime::libtorch ? "NAME.pt"
                                                                   : "NAME.pt and NAME.onnx") +
                           " as a path and under models/)");
  return load_center_detector(file, threads);
}

}  // namespace cropsight::nn
