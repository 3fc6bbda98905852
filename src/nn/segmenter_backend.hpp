#pragma once
// The interface between nn::PointSegmenter (in cropsight_nn, no libtorch) and its libtorch
// implementation, which lives in a plugin, libcropsight_nn_torch.so (src/nn/torch/), loaded with
// dlopen the first time a network is built or loaded.
//
// Why a plugin: linking libtorch into a program costs ~0.6 s at every start (the dynamic loader's
// relocations over libtorch_cpu and its operator registration: 0.97 s for `cropsight --version`
// with it, 0.38 s without, on the 2-core VM), which every broccoli, stereo or GBDT command paid
// for nothing. Internal header: only src/nn uses it.
#include <filesystem>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "cropsight/nn/point_segmenter.hpp"
#include "nn/detector_backend.hpp"

namespace cropsight::nn::detail {

/// Same contract as the PointSegmenter member of the same name.
class SegmenterBackend {
 public:
  virtual ~SegmenterBackend() = default;
  virtual const PointNetConfig& config() const = 0;
  virtual std::size_t parameter_count() const = 0;
  virtual std::pair<double, double> train_step(const std::vector<Cloud>& batch) = 0;
  virtual std::vector<EpochLog> train(const std::vector<Cloud>& train, const std::vector<Cloud>& val,
                                      const std::function<void(const EpochLog&)>& on_epoch) = 0;
  virtual std::vector<int> segment(const Cloud& cloud, int* passes_out, int votes, std::vector<float>* proba) const = 0;
  virtual std::vector<int> segment_sampled(const Cloud& cloud, bool farthest) const = 0;
  virtual std::vector<int> sample_for_pass(const Cloud& cloud, bool farthest, int pass) const = 0;
  virtual std::vector<int> predict_at(const Cloud& cloud, const std::vector<int>& idx, float angle_rad,
                                      std::vector<float>* proba) const = 0;
  virtual std::vector<std::vector<int>> predict_passes(const Cloud& cloud, const std::vector<std::vector<int>>& idx,
                                                       const std::vector<float>& angle_rad, int threads,
                                                       std::vector<std::vector<float>>* proba) const = 0;
  virtual void save(const std::filesystem::path& path) const = 0;
};

/// Bumped whenever SegmenterBackend, DetectorBackend, their configurations, EpochLog or Cloud
/// change layout: a plugin of another version is refused (it would be a build mix-up, never a
/// supported combination).
// 2: PointNetConfig::lovasz_weight; 3: the detector; 4: CenterNetConfig::mask_thresholds and
// DetectorBackend::set_mask_thresholds; 5: CenterNetConfig::mask_upsampling and flip_test,
// DetectorBackend::set_inference in place of set_mask_thresholds; 6: CenterNetConfig::mask_inputs,
// mask_inputs_flip_test and mask_dice_weight, DetectorBackend::forward at any input size;
// 7: SegmenterBackend::predict_passes.
inline constexpr int kBackendApiVersion = 7;

struct BackendApi {
  int version = 0;
  std::unique_ptr<SegmenterBackend> (*create)(const PointNetConfig& cfg) = nullptr;  ///< throws Error
  std::unique_ptr<SegmenterBackend> (*load)(const std::filesystem::path& path, int threads) = nullptr;
  std::unique_ptr<DetectorBackend> (*create_detector)(const CenterNetConfig& cfg) = nullptr;  ///< throws Error
  std::unique_ptr<DetectorBackend> (*load_detector)(const std::filesystem::path& path, int threads) = nullptr;
};

/// The plugin's table, loaded on first use (point_segmenter.cpp says where it is looked for).
/// Throws Error when no plugin of this version is found.
const BackendApi& backend_api();

/// The plugin's one exported symbol.
inline constexpr const char* kBackendEntry = "cropsight_nn_backend";
inline constexpr const char* kBackendFile = "libcropsight_nn_torch.so";

}  // namespace cropsight::nn::detail

extern "C" const cropsight::nn::detail::BackendApi* cropsight_nn_backend();
