#pragma once
// Writes nn::CenterNet's ONNX graph (include/cropsight/nn/center_onnx.hpp) from the folded
// convolutions of the backend, wired as the libtorch forward pass (center_net_torch.cpp,
// NetImpl::forward) wires them; the test "same boxes from libtorch and OpenCV DNN" holds the two
// together. Also reads the metadata back. Internal header.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cropsight/nn/center_net.hpp"
#include "nn/detector_backend.hpp"

namespace cropsight::nn {

void write_center_onnx(const CenterNetConfig& cfg, const std::vector<detail::FoldedConv>& convs,
                       const std::filesystem::path& path);

/// The "cropsight.*" metadata of an ONNX file (keys without the prefix) and its output names.
/// Throws Error(path, ...) when the file is not an ONNX model.
struct OnnxModelInfo {
  std::map<std::string, std::string> metadata;
  std::vector<std::string> outputs;
};
OnnxModelInfo read_onnx_info(const std::filesystem::path& path);

}  // namespace cropsight::nn
