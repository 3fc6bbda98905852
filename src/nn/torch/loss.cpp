// The loss declared in loss.hpp.
#include "nn/torch/loss.hpp"

#include <vector>

namespace cropsight::nn::torch_impl {

torch::Tensor lovasz_softmax(const torch::Tensor& p, const torch::Tensor& y) {
  std::vector<torch::Tensor> per_class;
  for (int64_t c = 0; c < p.size(1); ++c) {
    const auto fg = y.eq(c).to(p.dtype());
    if (fg.sum().item<float>() == 0.f) continue;  // absent from the batch: no IoU to lose
    const auto errors = (fg - p.select(1, c)).abs();
    const auto [sorted, order] = torch::sort(errors, /*dim=*/0, /*descending=*/true);
    const auto g = fg.index_select(0, order);
    const auto gts = g.sum();
    const auto jaccard = 1.0 - (gts - g.cumsum(0)) / (gts + (1.0 - g).cumsum(0));
    auto grad = jaccard.clone();
    if (grad.size(0) > 1) grad.slice(0, 1).copy_(jaccard.slice(0, 1) - jaccard.slice(0, 0, -1));
    per_class.push_back(torch::dot(sorted, grad.detach()));
  }
  if (per_class.empty()) return torch::zeros({}, p.options());
  return torch::stack(per_class).mean();
}

torch::Tensor segmentation_loss(const torch::Tensor& logits, const torch::Tensor& y, const torch::Tensor& weights,
                                double lovasz_weight) {
  auto loss =
      torch::nn::functional::cross_entropy(logits, y, torch::nn::functional::CrossEntropyFuncOptions().weight(weights));
  if (lovasz_weight > 0) loss = loss + lovasz_weight * lovasz_softmax(torch::softmax(logits, 1), y);
  return loss;
}

}  // namespace cropsight::nn::torch_impl
