#pragma once
// Data preparation for the point networks: a cloud's positions normalised to the unit sphere
// plus the channels its feature set selects, and batches of sampled points as tensors (with the
// training augmentation). Internal header of the libtorch plugin (src/nn/torch/ only).
#include <torch/torch.h>

#include <Eigen/Core>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "cropsight/nn/point_segmenter.hpp"

namespace cropsight::nn::torch_impl {

// A cloud prepared for the network: normalised positions plus the selected channels.
struct Prepared {
  std::vector<Eigen::Vector3f> xyz, n, rgb;
  std::vector<int> labels;
};

// Throws Error("point network", ...) when `features` needs normals or colours the cloud lacks.
Prepared prepare(const Cloud& c, const std::string& features);

// Rotation by `a` radians about the vertical axis, y in the camera frame (y down): the training
// augmentation and the test-time votes.
Eigen::Matrix3f rotation_about_vertical(float a);

// Builds a batch from (cloud, point indices) pairs: xyz (B, N, 3), features (B, N, C) in the
// channel order x y z [r g b] [nx ny nz], labels (B, N) int64 (0 for unlabelled clouds). With
// `aug`, each cloud gets a random rotation about the vertical, scale, colour shift and per-point
// jitter drawn from it; else `rotation` (when given) rotates every cloud.
std::tuple<torch::Tensor, torch::Tensor, torch::Tensor> make_batch(const PointNetConfig& cfg,
                                                                   const std::vector<const Prepared*>& clouds,
                                                                   const std::vector<std::vector<int>>& idx,
                                                                   std::mt19937_64* aug,
                                                                   const Eigen::Matrix3f* rotation = nullptr);

}  // namespace cropsight::nn::torch_impl
