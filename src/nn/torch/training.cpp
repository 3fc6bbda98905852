// TorchSegmenter's training: class weights from the labels, Adam with step decay, shuffled
// batches of randomly sampled points (augmented), periodic validation mIoU, checkpoints.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "cropsight/core/class_scores.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/geometry/farthest_point.hpp"
#include "nn/torch/archive.hpp"
#include "nn/torch/loss.hpp"
#include "nn/torch/segmenter_impl.hpp"

namespace cropsight::nn {

using torch_impl::Prepared;

namespace {

// The training clouds prepared for the network; each must carry labels.
std::vector<Prepared> prepare_training(const std::vector<Cloud>& train, const std::string& features) {
  std::vector<Prepared> tr;
  for (const auto& c : train) {
    if (!c.has_labels()) throw Error("train", "training cloud without labels");
    tr.push_back(torch_impl::prepare(c, features));
  }
  return tr;
}

// Cross-entropy class weights from the training labels (inverse frequency, softened).
torch::Tensor class_weights(const std::vector<Prepared>& tr, const PointNetConfig& cfg) {
  std::vector<double> count(std::size_t(cfg.num_classes), 0.0);
  for (const auto& p : tr)
    for (int l : p.labels) {
      if (l < 0 || l >= cfg.num_classes) throw Error("train", "label " + std::to_string(l) + " out of range");
      count[std::size_t(l)] += 1;
    }
  const std::vector<double> weights = median_frequency_weights(count, cfg.class_weight_power);
  torch::Tensor w = torch::ones({cfg.num_classes});
  for (int c = 0; c < cfg.num_classes; ++c) w[c] = float(weights[std::size_t(c)]);
  return w;
}

// Confusion counts pooled over the points of several clouds, and their mean IoU over the classes
// present in truth or prediction (the validation figure of an epoch).
struct PooledIou {
  std::vector<double> tp, t, pr;  // true positives, truth counts, prediction counts per class
  explicit PooledIou(int classes) : tp(std::size_t(classes)), t(tp), pr(tp) {}
  void add(const std::vector<int>& labels, const std::vector<int>& pred) {
    for (std::size_t i = 0; i < pred.size(); ++i) {
      t[std::size_t(labels[i])] += 1, pr[std::size_t(pred[i])] += 1;
      if (pred[i] == labels[i]) tp[std::size_t(pred[i])] += 1;
    }
  }
  double mean() const {
    double s = 0;
    int k = 0;
    for (std::size_t c = 0; c < tp.size(); ++c)
      if (t[c] + pr[c] > 0) s += tp[c] / (t[c] + pr[c] - tp[c]), ++k;
    return k ? s / k : 0;
  }
};

}  // namespace

void TorchSegmenter::Impl::make_optimizer() {
  opt = std::make_unique<torch::optim::Adam>(net->parameters(),
                                             torch::optim::AdamOptions(cfg.lr).weight_decay(cfg.weight_decay));
}

void TorchSegmenter::Impl::set_lr(double lr) {
  for (auto& g : opt->param_groups()) static_cast<torch::optim::AdamOptions&>(g.options()).lr(lr);
}

std::pair<double, double> TorchSegmenter::Impl::step(const torch::Tensor& xyz, const torch::Tensor& feats,
                                                     const torch::Tensor& labels) {
  net->train();
  if (!opt) make_optimizer();
  opt->zero_grad();
  auto logits = net->forward(xyz, feats);
  auto flat = logits.reshape({-1, cfg.num_classes});
  auto y = labels.reshape({-1});
  auto loss = torch_impl::segmentation_loss(flat, y, class_weights, cfg.lovasz_weight);
  loss.backward();
  opt->step();
  const double acc = flat.argmax(1).eq(y).to(torch::kDouble).mean().item<double>();
  return {loss.item<double>(), acc};
}

std::pair<double, double> TorchSegmenter::Impl::train_epoch(const std::vector<Prepared>& tr, std::mt19937_64& rng) {
  std::vector<int> order(tr.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  double loss_sum = 0, acc_sum = 0;
  int steps = 0;
  for (std::size_t b0 = 0; b0 < order.size(); b0 += std::size_t(cfg.batch_size)) {
    const std::size_t b1 = std::min(order.size(), b0 + std::size_t(cfg.batch_size));
    if (b1 - b0 < 2 && order.size() >= 2) continue;  // BatchNorm needs more than one cloud
    std::vector<const Prepared*> ptrs;
    std::vector<std::vector<int>> idx;
    for (std::size_t k = b0; k < b1; ++k) {
      const Prepared& p = tr[std::size_t(order[k])];
      ptrs.push_back(&p);
      idx.push_back(geometry::random_sample(p.xyz.size(), std::size_t(cfg.num_points), rng()));
    }
    auto [xyz, feats, labels] = torch_impl::make_batch(cfg, ptrs, idx, cfg.augment ? &rng : nullptr);
    auto [l, a] = step(xyz, feats, labels);
    loss_sum += l, acc_sum += a, ++steps;
  }
  return {steps ? loss_sum / steps : 0, steps ? acc_sum / steps : 0};
}

double TorchSegmenter::Impl::validation_miou(const std::vector<Prepared>& va) const {
  PooledIou iou(cfg.num_classes);
  for (const auto& p : va) iou.add(p.labels, predict(p, nullptr));
  return iou.mean();
}

std::pair<double, double> TorchSegmenter::train_step(const std::vector<Cloud>& batch) {
  std::vector<Prepared> prep;
  for (const auto& c : batch) prep.push_back(torch_impl::prepare(c, impl_->cfg.features));
  std::vector<const Prepared*> ptrs;
  std::vector<std::vector<int>> idx;
  for (const auto& p : prep) {
    ptrs.push_back(&p);
    idx.push_back(geometry::random_sample(p.xyz.size(), std::size_t(impl_->cfg.num_points), impl_->cfg.seed));
  }
  auto [xyz, feats, labels] = torch_impl::make_batch(impl_->cfg, ptrs, idx, nullptr);
  return impl_->step(xyz, feats, labels);
}

std::vector<EpochLog> TorchSegmenter::train(const std::vector<Cloud>& train, const std::vector<Cloud>& val,
                                            const std::function<void(const EpochLog&)>& on_epoch) {
  auto& I = *impl_;
  const auto& cfg = I.cfg;
  if (train.empty()) throw Error("train", "no training clouds");
  const std::vector<Prepared> tr = prepare_training(train, cfg.features);
  std::vector<Prepared> va;
  for (const auto& c : val) va.push_back(torch_impl::prepare(c, cfg.features));
  I.class_weights = class_weights(tr, cfg);
  if (!I.opt) I.make_optimizer();
  if (!cfg.checkpoint.empty() && std::filesystem::exists(cfg.checkpoint))
    I.epochs_done = torch_impl::read_checkpoint(cfg.checkpoint, *I.net, *I.opt);

  std::vector<EpochLog> logs;
  std::mt19937_64 rng(cfg.seed * 7919 + std::uint64_t(I.epochs_done));
  for (int epoch = I.epochs_done; epoch < cfg.epochs; ++epoch) {
    const Stopwatch clock;
    EpochLog log;
    log.epoch = epoch + 1;
    log.lr = cfg.lr * std::pow(cfg.lr_decay, epoch / std::max(1, cfg.lr_step));
    I.set_lr(log.lr);
    torch::manual_seed(cfg.seed + std::uint64_t(epoch));  // dropout masks: deterministic per epoch
    std::tie(log.loss, log.train_acc) = I.train_epoch(tr, rng);
    if (!va.empty() && cfg.val_every > 0 && ((epoch + 1) % cfg.val_every == 0 || epoch + 1 == cfg.epochs))
      log.val_miou = I.validation_miou(va);  // over the pooled points of every validation cloud
    log.seconds = clock.seconds();
    I.epochs_done = epoch + 1;
    if (!cfg.checkpoint.empty()) torch_impl::write_checkpoint(cfg.checkpoint, *I.net, *I.opt, I.epochs_done);
    logs.push_back(log);
    if (on_epoch) on_epoch(log);
  }
  return logs;
}

}  // namespace cropsight::nn
