#pragma once
// TorchSegmenter's state: the configuration, the network, the optimiser and the training
// progress. Internal header of the libtorch plugin (src/nn/torch/ only).
#include <torch/torch.h>

#include <memory>
#include <utility>
#include <vector>

#include "nn/torch/layers.hpp"
#include "nn/torch/point_batch.hpp"
#include "nn/torch/torch_segmenter.hpp"

namespace cropsight::nn {

struct TorchSegmenter::Impl {
  PointNetConfig cfg;
  mutable torch_impl::SegNet net{nullptr};  // eval-mode forward passes from const methods
  std::unique_ptr<torch::optim::Adam> opt;
  torch::Tensor class_weights;  // (classes) float
  int epochs_done = 0;

  explicit Impl(const PointNetConfig& c);  // torch_segmenter.cpp

  // training.cpp
  void make_optimizer();
  void set_lr(double lr);
  // One optimiser step on a batch: (loss, accuracy on the batch's points).
  std::pair<double, double> step(const torch::Tensor& xyz, const torch::Tensor& feats, const torch::Tensor& labels);
  // One pass over `tr` in an order shuffled with `rng`, batches of cfg.batch_size clouds with
  // cfg.num_points points drawn from `rng`: (mean loss, mean accuracy) over the steps.
  std::pair<double, double> train_epoch(const std::vector<torch_impl::Prepared>& tr, std::mt19937_64& rng);
  // mIoU of predict() over the pooled points of the labelled clouds `va`.
  double validation_miou(const std::vector<torch_impl::Prepared>& va) const;

  // inference.cpp. Predicted labels for every point of a prepared cloud: random disjoint chunks.
  // With votes > 1 the cloud is covered `votes` times, each time with another chunking (seed + v)
  // and rotated by 2πv/votes about the vertical axis (the rotation training augments with), and
  // the per-point class probabilities are averaged (test-time augmentation). votes = 1 is one
  // cover without rotation.
  std::vector<int> predict(const torch_impl::Prepared& p, int* passes, int votes = 1,
                           std::vector<float>* proba_out = nullptr) const;
  // One forward pass on the num_points samples `idx` of a prepared cloud, rotated by `angle`
  // about the vertical axis: labels, and probabilities into `proba` when given. Needs
  // no-grad and eval mode set by the caller (both are per call site: no-grad is per thread).
  std::vector<int> forward_pass(const torch_impl::Prepared& p, const std::vector<int>& idx, float angle,
                                std::vector<float>* proba) const;
};

}  // namespace cropsight::nn
