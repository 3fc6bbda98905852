#pragma once
// The interface between nn::CenterNet (in cropsight_nn, no libtorch) and its libtorch
// implementation in the network plugin (src/nn/torch/center_net_torch.cpp). It travels in the
// plugin's one ABI table (segmenter_backend.hpp, BackendApi::create_detector / load_detector).
// Plain arrays only: the targets are encoded and the heads decoded on this side
// (center_codec.hpp). Internal header: only src/nn uses it.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/nn/center_net.hpp"

namespace cropsight::nn::detail {

/// A training batch of n images, every array image-major (center_codec.hpp's CenterTargets
/// concatenated): images n*3*H*W, heatmap and mask n*C*oh*ow, index and reg_mask n*K, size and
/// offset n*K*2; mask_present n (1 = that image's mask is supervised; mask is zeros otherwise).
struct DetectorBatch {
  int n = 0;
  std::vector<float> images, heatmap, size, offset, reg_mask, mask, mask_present;
  std::vector<std::int64_t> index;
};

/// One convolution of the trained network with its BatchNorm folded in (W' = W g / sqrt(v + e),
/// b' = beta - m g / sqrt(v + e)): what the ONNX export writes. weight is (out, in, k, k).
struct FoldedConv {
  std::string name;  ///< the module path, e.g. "s0a", "lat2", "hm.hidden", "hm.out"
  int out = 0, in = 0, kernel = 1, stride = 1;
  bool relu = false;  ///< followed by ReLU
  std::vector<float> weight, bias;
};

class DetectorBackend {
 public:
  virtual ~DetectorBackend() = default;
  virtual const CenterNetConfig& config() const = 0;
  virtual std::size_t parameter_count() const = 0;
  virtual void set_lr(double lr) = 0;
  virtual DetectorLosses train_step(const DetectorBatch& batch) = 0;
  /// Eval-mode heads of n images of width x height pixels (n*3*height*width floats; any multiple
  /// of 32, not only the configured input: the network is fully convolutional).
  virtual std::vector<CenterNetHeads> forward(const std::vector<float>& images, int n, int width, int height) const = 0;
  virtual void save(const std::filesystem::path& path) const = 0;
  /// Replaces the inference settings of config() with those of `cfg` (already validated by the
  /// caller): input size, mask thresholds, mask upsampling, flip test, mask inputs. The weights are unchanged.
  virtual void set_inference(const CenterNetConfig& cfg) = 0;
  /// Every convolution, folded, by name (center_onnx.cpp wires them as forward() does).
  virtual std::vector<FoldedConv> folded_convs() const = 0;
  /// Weights, optimiser state and epochs done (training checkpoints, written atomically).
  virtual void write_checkpoint(const std::filesystem::path& path, int epochs_done) const = 0;
  /// Restores a checkpoint of write_checkpoint; returns its epochs done. Throws Error(path).
  virtual int read_checkpoint(const std::filesystem::path& path) = 0;
};

}  // namespace cropsight::nn::detail
