#pragma once
// The libtorch backend behind nn::PointSegmenter (same contract, documented in
// point_segmenter.hpp), built into the plugin libcropsight_nn_torch.so (src/nn/CMakeLists.txt).
// Its members are defined by job: torch_segmenter.cpp (construction), training.cpp,
// inference.cpp, archive.cpp (model files); plugin.cpp exports it. No libtorch include here:
// the state is behind a pimpl (segmenter_impl.hpp).
#include <filesystem>
#include <memory>

#include "nn/segmenter_backend.hpp"

namespace cropsight::nn {

class TorchSegmenter final : public detail::SegmenterBackend {
 public:
  explicit TorchSegmenter(const PointNetConfig& cfg);
  ~TorchSegmenter() override;
  const PointNetConfig& config() const override;
  std::size_t parameter_count() const override;
  std::pair<double, double> train_step(const std::vector<Cloud>& batch) override;
  std::vector<EpochLog> train(const std::vector<Cloud>& train, const std::vector<Cloud>& val,
                              const std::function<void(const EpochLog&)>& on_epoch) override;
  std::vector<int> segment(const Cloud& cloud, int* passes_out, int votes, std::vector<float>* proba) const override;
  std::vector<int> segment_sampled(const Cloud& cloud, bool farthest) const override;
  std::vector<int> sample_for_pass(const Cloud& cloud, bool farthest, int pass) const override;
  std::vector<int> predict_at(const Cloud& cloud, const std::vector<int>& idx, float angle_rad,
                              std::vector<float>* proba) const override;
  std::vector<std::vector<int>> predict_passes(const Cloud& cloud, const std::vector<std::vector<int>>& idx,
                                               const std::vector<float>& angle_rad, int threads,
                                               std::vector<std::vector<float>>* proba) const override;
  void save(const std::filesystem::path& path) const override;
  static std::unique_ptr<detail::SegmenterBackend> load(const std::filesystem::path& path, int threads);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cropsight::nn
