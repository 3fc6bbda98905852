#pragma once
// The training loss of the point networks: class-weighted cross-entropy, optionally plus a
// weighted Lovász-softmax term. Internal header of the libtorch plugin (src/nn/torch/ only).
#include <torch/torch.h>

namespace cropsight::nn::torch_impl {

// Lovász-softmax (Berman et al., CVPR 2018): the convex surrogate of 1 − IoU for each class present
// in the batch, averaged: per class, the points' errors |[y = c] − p_c| sorted in decreasing order,
// weighted by the Jaccard loss's increments along that order. `p`: (points, classes) softmax,
// `y`: (points) int64 labels.
torch::Tensor lovasz_softmax(const torch::Tensor& p, const torch::Tensor& y);

// Cross-entropy of `logits` (points, classes) against `y` (points) with per-class `weights`,
// plus lovasz_weight × lovasz_softmax when lovasz_weight > 0.
torch::Tensor segmentation_loss(const torch::Tensor& logits, const torch::Tensor& y, const torch::Tensor& weights,
                                double lovasz_weight);

}  // namespace cropsight::nn::torch_impl
