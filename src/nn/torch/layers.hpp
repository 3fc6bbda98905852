#pragma once
// The network layers of PointNet++ (MSG) and PointResNet (Qi et al.; Luo et al.), with two
// deliberate simplifications for speed on two cores, documented in
// docs/pipelines/grape-bunches.md: k-nearest-neighbour grouping instead of ball query, and
// farthest-point sampling done in C++ (geometry::farthest_point_sample) outside autograd.
// Internal header of the libtorch plugin (src/nn/torch/ only).
#include <torch/torch.h>

#include <utility>
#include <vector>

#include "cropsight/nn/point_segmenter.hpp"

namespace cropsight::nn::torch_impl {

// Linear over the last dimension followed by BatchNorm over every other dimension.
struct LinBnImpl : torch::nn::Module {
  torch::nn::Linear lin{nullptr};
  torch::nn::BatchNorm1d bn{nullptr};
  LinBnImpl(int in, int out);
  torch::Tensor forward(const torch::Tensor& x);
};
TORCH_MODULE(LinBn);

// ResMLP block (PointResNet): relu(x' + F(x')) with x' = relu(BN(W0 x)) and
// F = BN(W2 relu(BN(W1 .))). The projection W0 makes the residual widths match.
struct MlpBlockImpl : torch::nn::Module {
  bool residual;
  LinBn proj{nullptr}, f1{nullptr}, f2{nullptr};
  MlpBlockImpl(int in, int out, bool res);
  torch::Tensor forward(const torch::Tensor& x);
};
TORCH_MODULE(MlpBlock);

// Set abstraction: S centroids, one or more kNN scales, each scale an MLP block then max-pool.
struct SetAbstractionImpl : torch::nn::Module {
  int S;
  std::vector<int> ks;
  std::vector<MlpBlock> branches;
  SetAbstractionImpl(int S_, std::vector<int> ks_, int in, std::vector<int> outs, bool residual);
  std::pair<torch::Tensor, torch::Tensor> forward(const torch::Tensor& xyz, const torch::Tensor& feats);
};
TORCH_MODULE(SetAbstraction);

// Feature propagation: inverse-distance interpolation from the 3 nearest coarse points, skip
// concatenation, MLP block.
struct FeaturePropImpl : torch::nn::Module {
  MlpBlock mlp{nullptr};
  FeaturePropImpl(int in, int out, bool residual);
  torch::Tensor forward(const torch::Tensor& xyz1, const torch::Tensor& xyz2, const torch::Tensor& f1,
                        const torch::Tensor& f2);
};
TORCH_MODULE(FeatureProp);

// The whole segmentation network: three set abstractions, three feature propagations, a
// two-layer per-point classifier.
struct SegNetImpl : torch::nn::Module {
  SetAbstraction sa1{nullptr}, sa2{nullptr}, sa3{nullptr};
  FeatureProp fp3{nullptr}, fp2{nullptr}, fp1{nullptr};
  LinBn head1{nullptr};
  torch::nn::Dropout drop{nullptr};
  torch::nn::Linear head2{nullptr};
  explicit SegNetImpl(const PointNetConfig& c);
  // xyz (B, N, 3), feats (B, N, C) → logits (B, N, classes)
  torch::Tensor forward(const torch::Tensor& xyz, const torch::Tensor& feats);
};
TORCH_MODULE(SegNet);

}  // namespace cropsight::nn::torch_impl
