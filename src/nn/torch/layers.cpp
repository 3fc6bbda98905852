// The layers declared in layers.hpp: the forward passes of PointNet++ (MSG) and PointResNet.
#include "nn/torch/layers.hpp"

#include <algorithm>
#include <string>

#include "cropsight/geometry/farthest_point.hpp"

namespace cropsight::nn::torch_impl {

namespace {

// Rows of `points` (B, N, C) picked by `idx` (B, ...) → (B, ..., C).
torch::Tensor gather(const torch::Tensor& points, const torch::Tensor& idx) {
  const auto B = points.size(0), N = points.size(1), C = points.size(2);
  auto offs = torch::arange(B, idx.options()).mul(N);
  std::vector<int64_t> shape(idx.dim(), 1);
  shape[0] = B;
  auto flat = (idx + offs.view(shape)).reshape({-1});
  auto out_shape = idx.sizes().vec();
  out_shape.push_back(C);
  return points.reshape({B * N, C}).index_select(0, flat).view(out_shape);
}

// Farthest-point sampling per batch item (C++, no autograd) → (B, S) int64.
torch::Tensor fps(const torch::Tensor& xyz, int S) {
  const auto B = xyz.size(0), N = xyz.size(1);
  auto cpu = xyz.detach().contiguous();
  auto out = torch::empty({B, S}, torch::kLong);
  for (int64_t b = 0; b < B; ++b) {
    const float* p = cpu[b].data_ptr<float>();
    std::vector<Eigen::Vector3f> pts(static_cast<std::size_t>(N));
    for (int64_t i = 0; i < N; ++i) pts[std::size_t(i)] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
    auto idx = geometry::farthest_point_sample(pts, std::size_t(S), 0);
    while (int(idx.size()) < S) idx.push_back(idx[idx.size() % std::max<std::size_t>(1, idx.size())]);
    auto* o = out[b].data_ptr<int64_t>();
    for (int s = 0; s < S; ++s) o[s] = idx[std::size_t(s)];
  }
  return out;
}

}  // namespace

LinBnImpl::LinBnImpl(int in, int out) {
  lin = register_module("lin", torch::nn::Linear(torch::nn::LinearOptions(in, out).bias(false)));
  bn = register_module("bn", torch::nn::BatchNorm1d(out));
}

torch::Tensor LinBnImpl::forward(const torch::Tensor& x) {
  auto s = x.sizes().vec();
  auto y = lin(x.reshape({-1, s.back()}));
  y = bn(y);
  s.back() = y.size(1);
  return y.reshape(s);
}

MlpBlockImpl::MlpBlockImpl(int in, int out, bool res) : residual(res) {
  proj = register_module("proj", LinBn(in, out));
  f1 = register_module("f1", LinBn(out, out));
  if (residual) f2 = register_module("f2", LinBn(out, out));
}

torch::Tensor MlpBlockImpl::forward(const torch::Tensor& x) {
  auto h = torch::relu(proj(x));
  if (!residual) return torch::relu(f1(h));  // plain PointNet++ MLP: two layers
  return torch::relu(h + f2(torch::relu(f1(h))));
}

SetAbstractionImpl::SetAbstractionImpl(int S_, std::vector<int> ks_, int in, std::vector<int> outs, bool residual)
    : S(S_), ks(ks_) {
  for (std::size_t i = 0; i < ks.size(); ++i)
    branches.push_back(register_module("b" + std::to_string(i), MlpBlock(in + 3, outs[i], residual)));
}

std::pair<torch::Tensor, torch::Tensor> SetAbstractionImpl::forward(const torch::Tensor& xyz,
                                                                    const torch::Tensor& feats) {
  const int s = std::min<int>(S, int(xyz.size(1)));
  auto cidx = fps(xyz, s);
  auto new_xyz = gather(xyz, cidx);     // (B, S, 3)
  auto d = torch::cdist(new_xyz, xyz);  // (B, S, N)
  std::vector<torch::Tensor> outs;
  for (std::size_t i = 0; i < ks.size(); ++i) {
    const int k = std::min<int>(ks[i], int(xyz.size(1)));
    auto nidx = std::get<1>(d.topk(k, -1, /*largest=*/false));  // (B, S, k)
    auto rel = gather(xyz, nidx) - new_xyz.unsqueeze(2);        // (B, S, k, 3)
    // Relative positions are tiny in unit-sphere clouds: scale by the mean neighbour
    // distance of this layer so that the first linear layer sees O(1) inputs.
    rel = rel / (rel.norm(2, -1).mean().detach() + 1e-6);
    auto g = torch::cat({rel, gather(feats, nidx)}, -1);
    outs.push_back(std::get<0>(branches[i]->forward(g).max(2)));
  }
  return {new_xyz, torch::cat(outs, -1)};
}

FeaturePropImpl::FeaturePropImpl(int in, int out, bool residual) {
  mlp = register_module("mlp", MlpBlock(in, out, residual));
}

torch::Tensor FeaturePropImpl::forward(const torch::Tensor& xyz1, const torch::Tensor& xyz2, const torch::Tensor& f1,
                                       const torch::Tensor& f2) {
  const int k = std::min<int>(3, int(xyz2.size(1)));
  auto d = torch::cdist(xyz1, xyz2);
  auto [dist, idx] = d.topk(k, -1, false);
  auto w = 1.0 / (dist + 1e-8);
  w = w / w.sum(-1, true);
  auto interp = (gather(f2, idx) * w.unsqueeze(-1)).sum(2);
  return mlp->forward(torch::cat({f1, interp}, -1));
}

SegNetImpl::SegNetImpl(const PointNetConfig& c) {
  const int cin = feature_channels(c.features), w = c.width;
  const bool res = c.arch == "pointresnet";
  auto scales = [&](int k) { return res ? std::vector<int>{k} : std::vector<int>{std::max(4, k / 2), k}; };
  auto widths = [&](int o) { return res ? std::vector<int>{o} : std::vector<int>{o / 2, o / 2}; };
  sa1 = register_module("sa1", SetAbstraction(c.sa1_points, scales(c.k1), cin, widths(2 * w), res));
  sa2 = register_module("sa2", SetAbstraction(c.sa2_points, scales(c.k2), 2 * w, widths(4 * w), res));
  sa3 = register_module("sa3", SetAbstraction(c.sa3_points, scales(c.k3), 4 * w, widths(8 * w), res));
  fp3 = register_module("fp3", FeatureProp(8 * w + 4 * w, 4 * w, res));
  fp2 = register_module("fp2", FeatureProp(4 * w + 2 * w, 2 * w, res));
  fp1 = register_module("fp1", FeatureProp(2 * w + cin, 2 * w, res));
  head1 = register_module("head1", LinBn(2 * w, 2 * w));
  drop = register_module("drop", torch::nn::Dropout(c.dropout));
  head2 = register_module("head2", torch::nn::Linear(2 * w, c.num_classes));
}

torch::Tensor SegNetImpl::forward(const torch::Tensor& xyz, const torch::Tensor& feats) {
  auto [x1, f1] = sa1->forward(xyz, feats);
  auto [x2, f2] = sa2->forward(x1, f1);
  auto [x3, f3] = sa3->forward(x2, f2);
  auto g2 = fp3->forward(x2, x3, f2, f3);
  auto g1 = fp2->forward(x1, x2, f1, g2);
  auto g0 = fp1->forward(xyz, x1, feats, g1);
  return head2(drop(torch::relu(head1(g0))));
}

}  // namespace cropsight::nn::torch_impl
