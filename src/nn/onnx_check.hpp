#pragma once
// Internal to nn: an ONNX file's tensors checked before OpenCV's importer reads them. OpenCV 4.6
// copies an initializer's raw_data for as many elements as its dims say, without comparing the
// two: a file whose weights are shorter than their shape (a truncated or damaged export) made it
// read past the buffer (fuzz_onnx_model; fuzz/regressions/onnx_model/). Every tensor of the
// graph (initializers, Constant attributes, subgraphs) must hold exactly its shape's data, and
// every value a node reads must be defined in the model (OpenCV dereferenced a missing Conv
// weight: address 0).
#include <filesystem>

namespace cropsight::nn {

/// Throws Error(path, ...) for a file that is not an ONNX model or whose tensors do not hold
/// their shapes' data. Without libonnx-dev at build time it checks nothing.
void check_onnx_tensors(const std::filesystem::path& path);

}  // namespace cropsight::nn
