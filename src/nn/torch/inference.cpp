// TorchSegmenter's inference: whole clouds in disjoint chunks (with test-time rotation votes),
// and single passes on given samples.
#include <algorithm>
#include <cmath>
#include <exception>
#include <thread>

#include "cropsight/core/class_scores.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/geometry/farthest_point.hpp"
#include "nn/torch/segmenter_impl.hpp"
#include "nn/torch/torch_detector.hpp"

namespace cropsight::nn {

using torch_impl::Prepared;

std::vector<int> TorchSegmenter::Impl::predict(const Prepared& p, int* passes, int votes,
                                               std::vector<float>* proba_out) const {
  torch::NoGradGuard ng;
  net->eval();
  const std::size_t n = p.xyz.size(), N = std::size_t(cfg.num_points), C = std::size_t(cfg.num_classes);
  const std::size_t chunks = (n + N - 1) / N;
  std::vector<int> out(n, 0);
  const bool soft = votes > 1 || proba_out;
  std::vector<float> prob(soft ? n * C : 0, 0.f);
  const std::size_t per_batch = std::size_t(std::max(1, cfg.batch_size));
  for (int v = 0; v < votes; ++v) {
    const std::vector<int> perm = geometry::random_sample(n, n, cfg.seed + std::uint64_t(v));
    const Eigen::Matrix3f R = torch_impl::rotation_about_vertical(2.f * float(M_PI) * float(v) / float(votes));
    // Pad the last chunk with points drawn from the rest so every pass has N points.
    std::vector<std::vector<int>> idx(chunks);
    for (std::size_t c = 0; c < chunks; ++c)
      for (std::size_t i = 0; i < N; ++i) idx[c].push_back(perm[(c * N + i) % n]);
    for (std::size_t c0 = 0; c0 < chunks; c0 += per_batch) {
      const std::size_t c1 = std::min(chunks, c0 + per_batch);
      std::vector<const Prepared*> cl(c1 - c0, &p);
      std::vector<std::vector<int>> sub(idx.begin() + long(c0), idx.begin() + long(c1));
      auto [xyz, feats, labels] = torch_impl::make_batch(cfg, cl, sub, nullptr, v > 0 ? &R : nullptr);
      const auto logits = net->forward(xyz, feats);
      if (!soft) {
        auto pred = logits.argmax(-1).contiguous();
        const int64_t* pp = pred.data_ptr<int64_t>();
        for (std::size_t c = c0; c < c1; ++c)
          for (std::size_t i = 0; i < N && c * N + i < n; ++i)
            out[std::size_t(perm[c * N + i])] = int(pp[(c - c0) * N + i]);
        continue;
      }
      const auto sm = torch::softmax(logits, -1).contiguous();
      const float* ps = sm.data_ptr<float>();
      for (std::size_t c = c0; c < c1; ++c)
        for (std::size_t i = 0; i < N && c * N + i < n; ++i) {
          float* dst = &prob[std::size_t(perm[c * N + i]) * C];
          const float* src = ps + ((c - c0) * N + i) * C;
          for (std::size_t k = 0; k < C; ++k) dst[k] += src[k];
        }
    }
  }
  if (soft) out = argmax_rows(prob.data(), n, C);
  if (proba_out) {
    for (float& x : prob) x /= float(votes);
    *proba_out = std::move(prob);
  }
  if (passes) *passes = int(chunks) * votes;
  return out;
}

std::vector<int> TorchSegmenter::segment(const Cloud& cloud, int* passes, int votes, std::vector<float>* proba) const {
  if (votes < 1) throw Error("point network", "votes must be at least 1");
  if (cloud.empty()) return {};
  return impl_->predict(torch_impl::prepare(cloud, impl_->cfg.features), passes, votes, proba);
}

std::vector<int> TorchSegmenter::sample_for_pass(const Cloud& cloud, bool farthest, int pass) const {
  if (cloud.empty()) return {};
  if (pass < 0) throw Error("point network", "pass must be >= 0");
  const std::size_t n = std::size_t(impl_->cfg.num_points);
  // FPS is invariant to the unit-sphere normalisation, so it runs on the raw positions.
  auto idx = farthest ? geometry::farthest_point_sample(cloud.points, n, std::size_t(pass) * 7919 % cloud.size())
                      : geometry::random_sample(cloud.size(), n, impl_->cfg.seed + std::uint64_t(pass));
  while (idx.size() < n) idx.push_back(idx[idx.size() % cloud.size()]);
  return idx;
}

namespace {
void check_pass(const PointNetConfig& cfg, const Cloud& cloud, const std::vector<int>& idx) {
  if (idx.size() != std::size_t(cfg.num_points))
    throw Error("point network", "a pass needs exactly num_points = " + std::to_string(cfg.num_points) +
                                     " indices, got " + std::to_string(idx.size()));
  for (int i : idx)
    if (i < 0 || std::size_t(i) >= cloud.size()) throw Error("point network", "sample index out of range");
}
}  // namespace

std::vector<int> TorchSegmenter::Impl::forward_pass(const Prepared& p, const std::vector<int>& idx, float angle,
                                                    std::vector<float>* proba) const {
  const Eigen::Matrix3f R = torch_impl::rotation_about_vertical(angle);
  auto [xyz, feats, labels] = torch_impl::make_batch(cfg, {&p}, {idx}, nullptr, angle != 0.f ? &R : nullptr);
  const auto logits = net->forward(xyz, feats);
  if (proba) {
    const auto sm = torch::softmax(logits, -1).contiguous();
    proba->assign(sm.data_ptr<float>(), sm.data_ptr<float>() + sm.numel());
  }
  const auto pred = logits.argmax(-1).contiguous();
  return std::vector<int>(pred.data_ptr<int64_t>(), pred.data_ptr<int64_t>() + idx.size());
}

std::vector<int> TorchSegmenter::predict_at(const Cloud& cloud, const std::vector<int>& idx, float angle,
                                            std::vector<float>* proba) const {
  check_pass(impl_->cfg, cloud, idx);
  torch::NoGradGuard ng;
  impl_->net->eval();
  return impl_->forward_pass(torch_impl::prepare(cloud, impl_->cfg.features), idx, angle, proba);
}

std::vector<std::vector<int>> TorchSegmenter::predict_passes(const Cloud& cloud,
                                                             const std::vector<std::vector<int>>& idx,
                                                             const std::vector<float>& angles, int threads,
                                                             std::vector<std::vector<float>>* proba) const {
  if (angles.size() != idx.size()) throw Error("point network", "one angle per pass expected");
  for (const auto& one : idx) check_pass(impl_->cfg, cloud, one);
  const std::size_t passes = idx.size();
  std::vector<std::vector<int>> labels(passes);
  if (proba) proba->assign(passes, {});
  if (passes == 0) return labels;
  impl_->net->eval();  // here, once: the workers only read the network
  const Prepared p = torch_impl::prepare(cloud, impl_->cfg.features);
  const std::size_t workers = std::min(passes, std::size_t(std::max(1, threads)));
  // Worker w runs passes w, w + workers, ...; each pass writes only its own slots.
  auto run = [&](std::size_t w, bool own_thread) {
    torch::NoGradGuard ng;
    if (own_thread) torch_impl::set_operator_threads(1);
    for (std::size_t k = w; k < passes; k += workers)
      labels[k] = impl_->forward_pass(p, idx[k], angles[k], proba ? &(*proba)[k] : nullptr);
  };
  if (workers == 1) {
    run(0, false);
    return labels;
  }
  std::vector<std::exception_ptr> errors(workers);
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < workers; ++w)
    pool.emplace_back([&, w] {
      try {
        run(w, true);
      } catch (...) {
        errors[w] = std::current_exception();
      }
    });
  // The calling thread is worker 0, also one operator thread while the others run.
  const int before = torch_impl::set_operator_threads(1);
  try {
    run(0, false);
  } catch (...) {
    errors[0] = std::current_exception();
  }
  torch_impl::set_operator_threads(before);
  for (auto& t : pool) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  return labels;
}

std::vector<int> TorchSegmenter::segment_sampled(const Cloud& cloud, bool farthest) const {
  if (cloud.empty()) return {};
  const auto idx = sample_for_pass(cloud, farthest, 0);
  const auto sl = predict_at(cloud, idx, 0.f, nullptr);
  std::vector<Eigen::Vector3f> samples;
  for (int i : idx) samples.push_back(cloud.points[std::size_t(i)]);
  return geometry::carry_labels_back(samples, sl, cloud.points);
}

}  // namespace cropsight::nn
