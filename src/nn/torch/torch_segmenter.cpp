// PointNet++ (MSG) and PointResNet on libtorch, CPU. Layers follow Qi et al. (PointNet++) with
// two deliberate simplifications for speed on two cores, documented in
// docs/pipelines/grape-bunches.md: k-nearest-neighbour grouping instead of ball query, and
// farthest-point sampling done in C++ (geometry::farthest_point_sample) outside autograd.
//
// Built into the network backend plugin (libcropsight_nn_torch.so, see src/nn/CMakeLists.txt):
// the only code that includes or links libtorch. nn::PointSegmenter loads it on first use.
#include "cropsight/core/threads.hpp"
#include "nn/segmenter_backend.hpp"

#include <dlfcn.h>
#include <torch/torch.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>

#include "cropsight/core/class_scores.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/geometry/farthest_point.hpp"
#include "cropsight/geometry/knn_normals.hpp"
#include "cropsight/io/files.hpp"

namespace cropsight::nn {

namespace {
// libtorch's messages carry a multi-line C++ stack trace: the first line is the reason.
std::string torch_reason(const std::exception& e) {
  const auto* c = dynamic_cast<const c10::Error*>(&e);
  const std::string s = c ? c->what_without_backtrace() : e.what();
  return s.substr(0, s.find('\n'));
}

// Writes `a` to `path` through io::write_atomic_with (temporary sibling, then rename; removed on
// any failure), with libtorch's error reduced to one line.
void save_archive_atomic(torch::serialize::OutputArchive& a, const std::filesystem::path& path) {
  io::write_atomic_with(path, [&](const std::filesystem::path& tmp) {
    try {
      a.save_to(tmp.string());
    } catch (const std::exception& e) {
      throw Error(path.string(), "cannot write: " + torch_reason(e));
    }
  });
}
}  // namespace

namespace {

// Debian's libtorch does its GEMMs in OpenBLAS, whose own pthread pool (one worker per core,
// spinning while it waits) made a training epoch of the CPU-sized networks 2.2x slower on two
// cores (3.0-3.5 s vs 1.4 s per epoch with identical losses, --threads 1 or 2): these GEMMs are
// small, and torch's intra-op threads (--threads) already parallelise the work. So OpenBLAS runs
// single-threaded; looked up at run time because a libtorch built on another BLAS lacks it.
void single_threaded_blas() {
  using SetThreads = void (*)(int);
  if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) set(1);
}

// Linear over the last dimension followed by BatchNorm over every other dimension.
struct LinBnImpl : torch::nn::Module {
  torch::nn::Linear lin{nullptr};
  torch::nn::BatchNorm1d bn{nullptr};
  LinBnImpl(int in, int out) {
    lin = register_module("lin", torch::nn::Linear(torch::nn::LinearOptions(in, out).bias(false)));
    bn = register_module("bn", torch::nn::BatchNorm1d(out));
  }
  torch::Tensor forward(const torch::Tensor& x) {
    auto s = x.sizes().vec();
    auto y = lin(x.reshape({-1, s.back()}));
    y = bn(y);
    s.back() = y.size(1);
    return y.reshape(s);
  }
};
TORCH_MODULE(LinBn);

// ResMLP block (PointResNet): relu(x' + F(x')) with x' = relu(BN(W0 x)) and
// F = BN(W2 relu(BN(W1 .))). The projection W0 makes the residual widths match.
struct MlpBlockImpl : torch::nn::Module {
  bool residual;
  LinBn proj{nullptr}, f1{nullptr}, f2{nullptr};
  MlpBlockImpl(int in, int out, bool res) : residual(res) {
    proj = register_module("proj", LinBn(in, out));
    f1 = register_module("f1", LinBn(out, out));
    if (residual) f2 = register_module("f2", LinBn(out, out));
  }
  torch::Tensor forward(const torch::Tensor& x) {
    auto h = torch::relu(proj(x));
    if (!residual) return torch::relu(f1(h));  // plain PointNet++ MLP: two layers
    return torch::relu(h + f2(torch::relu(f1(h))));
  }
};
TORCH_MODULE(MlpBlock);

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

// Set abstraction: S centroids, one or more kNN scales, each scale an MLP block then max-pool.
struct SetAbstractionImpl : torch::nn::Module {
  int S;
  std::vector<int> ks;
  std::vector<MlpBlock> branches;
  SetAbstractionImpl(int S_, std::vector<int> ks_, int in, std::vector<int> outs, bool residual) : S(S_), ks(ks_) {
    for (std::size_t i = 0; i < ks.size(); ++i)
      branches.push_back(register_module("b" + std::to_string(i), MlpBlock(in + 3, outs[i], residual)));
  }
  std::pair<torch::Tensor, torch::Tensor> forward(const torch::Tensor& xyz, const torch::Tensor& feats) {
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
};
TORCH_MODULE(SetAbstraction);

// Feature propagation: inverse-distance interpolation from the 3 nearest coarse points, skip
// concatenation, MLP block.
struct FeaturePropImpl : torch::nn::Module {
  MlpBlock mlp{nullptr};
  FeaturePropImpl(int in, int out, bool residual) { mlp = register_module("mlp", MlpBlock(in, out, residual)); }
  torch::Tensor forward(const torch::Tensor& xyz1, const torch::Tensor& xyz2, const torch::Tensor& f1,
                        const torch::Tensor& f2) {
    const int k = std::min<int>(3, int(xyz2.size(1)));
    auto d = torch::cdist(xyz1, xyz2);
    auto [dist, idx] = d.topk(k, -1, false);
    auto w = 1.0 / (dist + 1e-8);
    w = w / w.sum(-1, true);
    auto interp = (gather(f2, idx) * w.unsqueeze(-1)).sum(2);
    return mlp->forward(torch::cat({f1, interp}, -1));
  }
};
TORCH_MODULE(FeatureProp);

struct SegNetImpl : torch::nn::Module {
  SetAbstraction sa1{nullptr}, sa2{nullptr}, sa3{nullptr};
  FeatureProp fp3{nullptr}, fp2{nullptr}, fp1{nullptr};
  LinBn head1{nullptr};
  torch::nn::Dropout drop{nullptr};
  torch::nn::Linear head2{nullptr};
  explicit SegNetImpl(const PointNetConfig& c) {
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
  // xyz (B, N, 3), feats (B, N, C) → logits (B, N, classes)
  torch::Tensor forward(const torch::Tensor& xyz, const torch::Tensor& feats) {
    auto [x1, f1] = sa1->forward(xyz, feats);
    auto [x2, f2] = sa2->forward(x1, f1);
    auto [x3, f3] = sa3->forward(x2, f2);
    auto g2 = fp3->forward(x2, x3, f2, f3);
    auto g1 = fp2->forward(x1, x2, f1, g2);
    auto g0 = fp1->forward(xyz, x1, feats, g1);
    return head2(drop(torch::relu(head1(g0))));
  }
};
TORCH_MODULE(SegNet);

// A cloud prepared for the network: normalised positions plus the selected channels.
// Lovász-softmax (Berman et al., CVPR 2018): the convex surrogate of 1 − IoU for each class present
// in the batch, averaged: per class, the points' errors |[y = c] − p_c| sorted in decreasing order,
// weighted by the Jaccard loss's increments along that order. `p`: (points, classes) softmax.
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

struct Prepared {
  std::vector<Eigen::Vector3f> xyz, n, rgb;
  std::vector<int> labels;
};

Prepared prepare(const Cloud& c, const std::string& features) {
  const bool need_n = features.find('n') != std::string::npos && features != "xyz";
  const bool need_rgb = features.find("rgb") != std::string::npos;
  if (need_n && !c.has_normals()) throw Error("point network", "features '" + features + "' need normals");
  if (need_rgb && !c.has_colors()) throw Error("point network", "features '" + features + "' need colours");
  Prepared p;
  p.xyz = c.points;
  geometry::normalize_unit_sphere(p.xyz);
  if (need_n) p.n = c.normals;
  if (need_rgb) p.rgb = c.colors;
  p.labels = c.labels;
  return p;
}

// Rotation by `a` radians about the vertical axis, y in the camera frame (y down): the training
// augmentation and the test-time votes.
Eigen::Matrix3f rotation_about_vertical(float a) {
  Eigen::Matrix3f R;
  R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return R;
}

// Fills row i of xyz (N,3) and feats (N,C) from point `src` with the channel order x y z
// [r g b] [nx ny nz].
void fill_point(const Prepared& p, int src, float* xyz, float* f, const Eigen::Matrix3f& R, float scale,
                const Eigen::Vector3f& jitter, const Eigen::Vector3f& dcol) {
  const Eigen::Vector3f x = scale * (R * p.xyz[std::size_t(src)]) + jitter;
  xyz[0] = x.x(), xyz[1] = x.y(), xyz[2] = x.z();
  int k = 0;
  f[k++] = x.x(), f[k++] = x.y(), f[k++] = x.z();
  if (!p.rgb.empty()) {
    const Eigen::Vector3f c = (p.rgb[std::size_t(src)] + dcol).cwiseMax(0.f).cwiseMin(1.f);
    f[k++] = c.x(), f[k++] = c.y(), f[k++] = c.z();
  }
  if (!p.n.empty()) {
    const Eigen::Vector3f n = R * p.n[std::size_t(src)];
    f[k++] = n.x(), f[k++] = n.y(), f[k++] = n.z();
  }
}

}  // namespace

namespace {
// Loads `net`'s weights from `a`, checking that every tensor keeps its shape: libtorch's
// Module::load swaps in tensors of any shape (a checkpoint of another width or feature set would
// load, then crash in the first forward pass). Throws Error(where, ...).
void load_weights(torch::nn::Module& net, torch::serialize::InputArchive& a, const std::string& where) {
  std::vector<std::pair<std::string, std::vector<int64_t>>> shapes;
  for (const auto& p : net.named_parameters()) shapes.emplace_back(p.key(), p.value().sizes().vec());
  for (const auto& b : net.named_buffers()) shapes.emplace_back(b.key(), b.value().sizes().vec());
  try {
    net.load(a);
  } catch (const std::exception& e) {
    throw Error(where, "weights do not fit this network: " + torch_reason(e));
  }
  auto params = net.named_parameters();
  auto buffers = net.named_buffers();
  for (const auto& [key, shape] : shapes) {
    const torch::Tensor* t = params.find(key);
    if (!t) t = buffers.find(key);
    if (!t || t->sizes().vec() != shape)
      throw Error(where, "weights do not fit this network: '" + key +
                             "' has another shape (written with another arch, width or feature set?)");
  }
}
}  // namespace

// The backend behind nn::PointSegmenter (same contract, documented in point_segmenter.hpp).
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
  void save(const std::filesystem::path& path) const override;
  static std::unique_ptr<detail::SegmenterBackend> load(const std::filesystem::path& path, int threads);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct TorchSegmenter::Impl {
  PointNetConfig cfg;
  mutable SegNet net{nullptr};  // eval-mode forward passes from const methods
  std::unique_ptr<torch::optim::Adam> opt;
  torch::Tensor class_weights;  // (classes) float
  int epochs_done = 0;

  explicit Impl(const PointNetConfig& c) : cfg(c) {
    cfg.validate("point network");
    at::set_num_threads(cfg.threads);
    single_threaded_blas();
    torch::manual_seed(cfg.seed);
    net = SegNet(cfg);
    class_weights = torch::ones({cfg.num_classes});
  }

  void make_optimizer() {
    opt = std::make_unique<torch::optim::Adam>(net->parameters(),
                                               torch::optim::AdamOptions(cfg.lr).weight_decay(cfg.weight_decay));
  }

  void set_lr(double lr) {
    for (auto& g : opt->param_groups()) static_cast<torch::optim::AdamOptions&>(g.options()).lr(lr);
  }

  // Builds a batch from (cloud, point indices) pairs, with optional augmentation.
  std::tuple<torch::Tensor, torch::Tensor, torch::Tensor> batch(const std::vector<const Prepared*>& clouds,
                                                                const std::vector<std::vector<int>>& idx,
                                                                std::mt19937_64* aug,
                                                                const Eigen::Matrix3f* rotation = nullptr) const {
    const int64_t B = int64_t(clouds.size()), N = int64_t(idx[0].size()), C = feature_channels(cfg.features);
    auto xyz = torch::empty({B, N, 3});
    auto feats = torch::empty({B, N, C});
    auto labels = torch::zeros({B, N}, torch::kLong);
    for (int64_t b = 0; b < B; ++b) {
      Eigen::Matrix3f R = rotation ? *rotation : Eigen::Matrix3f::Identity();
      float scale = 1.f;
      Eigen::Vector3f dcol = Eigen::Vector3f::Zero();
      std::normal_distribution<float> g(0.f, float(cfg.jitter_sigma));
      if (aug) {
        std::uniform_real_distribution<float> u(0.f, 1.f);
        const float a = u(*aug) * 2.f * float(M_PI);
        R = rotation_about_vertical(a);
        scale = float(cfg.scale_min + (cfg.scale_max - cfg.scale_min) * u(*aug));
        const float cj = float(cfg.colour_jitter);
        dcol = Eigen::Vector3f::Constant((u(*aug) * 2 - 1) * cj) +
               Eigen::Vector3f((u(*aug) * 2 - 1), (u(*aug) * 2 - 1), (u(*aug) * 2 - 1)) * (cj / 2);
      }
      float* px = xyz[b].data_ptr<float>();
      float* pf = feats[b].data_ptr<float>();
      int64_t* pl = labels[b].data_ptr<int64_t>();
      for (int64_t i = 0; i < N; ++i) {
        const int src = idx[std::size_t(b)][std::size_t(i)];
        Eigen::Vector3f jit = Eigen::Vector3f::Zero();
        if (aug) jit = Eigen::Vector3f(g(*aug), g(*aug), g(*aug)).cwiseMax(-0.02f).cwiseMin(0.02f);
        fill_point(*clouds[std::size_t(b)], src, px + 3 * i, pf + C * i, R, scale, jit, dcol);
        if (!clouds[std::size_t(b)]->labels.empty()) pl[i] = clouds[std::size_t(b)]->labels[std::size_t(src)];
      }
    }
    return {xyz, feats, labels};
  }

  std::pair<double, double> step(const torch::Tensor& xyz, const torch::Tensor& feats, const torch::Tensor& labels) {
    net->train();
    if (!opt) make_optimizer();
    opt->zero_grad();
    auto logits = net->forward(xyz, feats);
    auto flat = logits.reshape({-1, cfg.num_classes});
    auto y = labels.reshape({-1});
    auto loss = torch::nn::functional::cross_entropy(
        flat, y, torch::nn::functional::CrossEntropyFuncOptions().weight(class_weights));
    if (cfg.lovasz_weight > 0) loss = loss + cfg.lovasz_weight * lovasz_softmax(torch::softmax(flat, 1), y);
    loss.backward();
    opt->step();
    const double acc = flat.argmax(1).eq(y).to(torch::kDouble).mean().item<double>();
    return {loss.item<double>(), acc};
  }

  // Predicted labels for every point of a prepared cloud: random disjoint chunks. With votes > 1
  // the cloud is covered `votes` times, each time with another chunking (seed + v) and rotated
  // by 2πv/votes about the vertical axis (the rotation training augments with), and the
  // per-point class probabilities are averaged (test-time augmentation). votes = 1 is one cover
  // without rotation.
  std::vector<int> predict(const Prepared& p, int* passes, int votes = 1,
                           std::vector<float>* proba_out = nullptr) const {
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
      const Eigen::Matrix3f R = rotation_about_vertical(2.f * float(M_PI) * float(v) / float(votes));
      // Pad the last chunk with points drawn from the rest so every pass has N points.
      std::vector<std::vector<int>> idx(chunks);
      for (std::size_t c = 0; c < chunks; ++c)
        for (std::size_t i = 0; i < N; ++i) idx[c].push_back(perm[(c * N + i) % n]);
      for (std::size_t c0 = 0; c0 < chunks; c0 += per_batch) {
        const std::size_t c1 = std::min(chunks, c0 + per_batch);
        std::vector<const Prepared*> cl(c1 - c0, &p);
        std::vector<std::vector<int>> sub(idx.begin() + long(c0), idx.begin() + long(c1));
        auto [xyz, feats, labels] = batch(cl, sub, nullptr, v > 0 ? &R : nullptr);
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
};

TorchSegmenter::TorchSegmenter(const PointNetConfig& cfg) : impl_(std::make_unique<Impl>(cfg)) {}
TorchSegmenter::~TorchSegmenter() = default;
const PointNetConfig& TorchSegmenter::config() const { return impl_->cfg; }

std::size_t TorchSegmenter::parameter_count() const {
  std::size_t n = 0;
  for (const auto& p : impl_->net->parameters()) n += std::size_t(p.numel());
  return n;
}

std::pair<double, double> TorchSegmenter::train_step(const std::vector<Cloud>& batch) {
  std::vector<Prepared> prep;
  for (const auto& c : batch) prep.push_back(prepare(c, impl_->cfg.features));
  std::vector<const Prepared*> ptrs;
  std::vector<std::vector<int>> idx;
  for (const auto& p : prep) {
    ptrs.push_back(&p);
    idx.push_back(geometry::random_sample(p.xyz.size(), std::size_t(impl_->cfg.num_points), impl_->cfg.seed));
  }
  auto [xyz, feats, labels] = impl_->batch(ptrs, idx, nullptr);
  return impl_->step(xyz, feats, labels);
}

std::vector<EpochLog> TorchSegmenter::train(const std::vector<Cloud>& train, const std::vector<Cloud>& val,
                                            const std::function<void(const EpochLog&)>& on_epoch) {
  auto& I = *impl_;
  const auto& cfg = I.cfg;
  if (train.empty()) throw Error("train", "no training clouds");
  std::vector<Prepared> tr, va;
  for (const auto& c : train) {
    if (!c.has_labels()) throw Error("train", "training cloud without labels");
    tr.push_back(prepare(c, cfg.features));
  }
  for (const auto& c : val) va.push_back(prepare(c, cfg.features));

  // Class weights from the training labels (inverse frequency, softened).
  std::vector<double> count(std::size_t(cfg.num_classes), 0.0);
  for (const auto& p : tr)
    for (int l : p.labels) {
      if (l < 0 || l >= cfg.num_classes) throw Error("train", "label " + std::to_string(l) + " out of range");
      count[std::size_t(l)] += 1;
    }
  const std::vector<double> weights = median_frequency_weights(count, cfg.class_weight_power);
  I.class_weights = torch::ones({cfg.num_classes});
  for (int c = 0; c < cfg.num_classes; ++c) I.class_weights[c] = float(weights[std::size_t(c)]);

  if (!I.opt) I.make_optimizer();
  // Resume. A bad checkpoint is the user's file: name it, with libtorch's one-line reason.
  if (!cfg.checkpoint.empty() && std::filesystem::exists(cfg.checkpoint)) {
    const std::string& where = cfg.checkpoint;
    if (!std::filesystem::is_regular_file(where)) throw Error(where, "not a checkpoint file (a directory?)");
    torch::serialize::InputArchive a, m, o;
    torch::Tensor e;
    try {
      a.load_from(where);
      a.read("model", m);
      a.read("optim", o);
      a.read("epoch", e);
    } catch (const std::exception& ex) {
      throw Error(where, "not a network checkpoint: " + torch_reason(ex));
    }
    load_weights(*I.net, m, where);
    try {
      I.opt->load(o);
      I.epochs_done = int(e.item<int64_t>());
    } catch (const std::exception& ex) {
      throw Error(where, "optimizer state does not fit this network: " + torch_reason(ex));
    }
  }

  std::vector<EpochLog> logs;
  std::mt19937_64 rng(cfg.seed * 7919 + std::uint64_t(I.epochs_done));
  for (int epoch = I.epochs_done; epoch < cfg.epochs; ++epoch) {
    const auto t0 = std::chrono::steady_clock::now();
    const double lr = cfg.lr * std::pow(cfg.lr_decay, epoch / std::max(1, cfg.lr_step));
    I.set_lr(lr);
    torch::manual_seed(cfg.seed + std::uint64_t(epoch));  // dropout masks: deterministic per epoch
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
      auto [xyz, feats, labels] = I.batch(ptrs, idx, cfg.augment ? &rng : nullptr);
      auto [l, a] = I.step(xyz, feats, labels);
      loss_sum += l, acc_sum += a, ++steps;
    }
    EpochLog log;
    log.epoch = epoch + 1;
    log.loss = steps ? loss_sum / steps : 0;
    log.train_acc = steps ? acc_sum / steps : 0;
    log.lr = lr;
    if (!va.empty() && cfg.val_every > 0 && ((epoch + 1) % cfg.val_every == 0 || epoch + 1 == cfg.epochs)) {
      // Validation mIoU over the pooled points of every validation cloud (classes present).
      std::vector<double> tp(std::size_t(cfg.num_classes)), t(tp), pr(tp);
      for (const auto& p : va) {
        const auto pred = I.predict(p, nullptr);
        for (std::size_t i = 0; i < pred.size(); ++i) {
          t[std::size_t(p.labels[i])] += 1, pr[std::size_t(pred[i])] += 1;
          if (pred[i] == p.labels[i]) tp[std::size_t(pred[i])] += 1;
        }
      }
      double s = 0;
      int k = 0;
      for (int c = 0; c < cfg.num_classes; ++c)
        if (t[std::size_t(c)] + pr[std::size_t(c)] > 0)
          s += tp[std::size_t(c)] / (t[std::size_t(c)] + pr[std::size_t(c)] - tp[std::size_t(c)]), ++k;
      log.val_miou = k ? s / k : 0;
    }
    log.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    I.epochs_done = epoch + 1;
    if (!cfg.checkpoint.empty()) {
      torch::serialize::OutputArchive a, m, o;
      I.net->save(m);
      I.opt->save(o);
      a.write("model", m);
      a.write("optim", o);
      a.write("epoch", torch::tensor(int64_t(I.epochs_done)));
      save_archive_atomic(a, cfg.checkpoint);
    }
    logs.push_back(log);
    if (on_epoch) on_epoch(log);
  }
  return logs;
}

std::vector<int> TorchSegmenter::segment(const Cloud& cloud, int* passes, int votes, std::vector<float>* proba) const {
  if (votes < 1) throw Error("point network", "votes must be at least 1");
  if (cloud.empty()) return {};
  return impl_->predict(prepare(cloud, impl_->cfg.features), passes, votes, proba);
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

std::vector<int> TorchSegmenter::predict_at(const Cloud& cloud, const std::vector<int>& idx, float angle,
                                            std::vector<float>* proba) const {
  if (idx.size() != std::size_t(impl_->cfg.num_points))
    throw Error("point network", "a pass needs exactly num_points = " + std::to_string(impl_->cfg.num_points) +
                                     " indices, got " + std::to_string(idx.size()));
  for (int i : idx)
    if (i < 0 || std::size_t(i) >= cloud.size()) throw Error("point network", "sample index out of range");
  torch::NoGradGuard ng;
  impl_->net->eval();
  const Prepared p = prepare(cloud, impl_->cfg.features);
  const Eigen::Matrix3f R = rotation_about_vertical(angle);
  auto [xyz, feats, labels] = impl_->batch({&p}, {idx}, nullptr, angle != 0.f ? &R : nullptr);
  const auto logits = impl_->net->forward(xyz, feats);
  if (proba) {
    const auto sm = torch::softmax(logits, -1).contiguous();
    proba->assign(sm.data_ptr<float>(), sm.data_ptr<float>() + sm.numel());
  }
  const auto pred = logits.argmax(-1).contiguous();
  return std::vector<int>(pred.data_ptr<int64_t>(), pred.data_ptr<int64_t>() + idx.size());
}

std::vector<int> TorchSegmenter::segment_sampled(const Cloud& cloud, bool farthest) const {
  if (cloud.empty()) return {};
  const auto idx = sample_for_pass(cloud, farthest, 0);
  const auto sl = predict_at(cloud, idx, 0.f, nullptr);
  std::vector<Eigen::Vector3f> samples;
  for (int i : idx) samples.push_back(cloud.points[std::size_t(i)]);
  return geometry::carry_labels_back(samples, sl, cloud.points);
}

namespace {
void put(torch::serialize::OutputArchive& a, const std::string& k, const std::string& v) { a.write(k, c10::IValue(v)); }
void put(torch::serialize::OutputArchive& a, const std::string& k, double v) { a.write(k, c10::IValue(v)); }
std::string get_s(torch::serialize::InputArchive& a, const std::string& k) {
  c10::IValue v;
  a.read(k, v);
  return v.toStringRef();
}
double get_d(torch::serialize::InputArchive& a, const std::string& k) {
  c10::IValue v;
  a.read(k, v);
  return v.toDouble();
}
}  // namespace

void TorchSegmenter::save(const std::filesystem::path& path) const {
  const auto& c = impl_->cfg;
  torch::serialize::OutputArchive a, m;
  impl_->net->save(m);
  a.write("model", m);
  put(a, "meta.kind", std::string("grape-pointnet"));
  put(a, "meta.arch", c.arch);
  put(a, "meta.features", c.features);
  put(a, "meta.num_classes", double(c.num_classes));
  put(a, "meta.num_points", double(c.num_points));
  put(a, "meta.sa1_points", double(c.sa1_points));
  put(a, "meta.sa2_points", double(c.sa2_points));
  put(a, "meta.sa3_points", double(c.sa3_points));
  put(a, "meta.k1", double(c.k1));
  put(a, "meta.k2", double(c.k2));
  put(a, "meta.k3", double(c.k3));
  put(a, "meta.width", double(c.width));
  put(a, "meta.seed", double(c.seed));
  put(a, "meta.batch_size", double(c.batch_size));
  save_archive_atomic(a, path);
}

std::unique_ptr<detail::SegmenterBackend> TorchSegmenter::load(const std::filesystem::path& path, int threads) {
  const std::string where = path.string();
  check_thread_count(threads, "threads");
  if (!std::filesystem::exists(path)) throw Error(where, "no such model file");
  if (!std::filesystem::is_regular_file(path)) throw Error(where, "not a model file (a directory?)");
  torch::serialize::InputArchive a;
  try {
    a.load_from(where);
  } catch (const std::exception& e) {
    throw Error(where, "not a cropsight network model: " + torch_reason(e));
  }
  PointNetConfig c;
  try {
    if (get_s(a, "meta.kind") != "grape-pointnet") throw Error(where, "not a grape network model");
    c.arch = get_s(a, "meta.arch");
    c.features = get_s(a, "meta.features");
    c.num_classes = int(get_d(a, "meta.num_classes"));
    c.num_points = int(get_d(a, "meta.num_points"));
    c.sa1_points = int(get_d(a, "meta.sa1_points"));
    c.sa2_points = int(get_d(a, "meta.sa2_points"));
    c.sa3_points = int(get_d(a, "meta.sa3_points"));
    c.k1 = int(get_d(a, "meta.k1"));
    c.k2 = int(get_d(a, "meta.k2"));
    c.k3 = int(get_d(a, "meta.k3"));
    c.width = int(get_d(a, "meta.width"));
    c.seed = std::uint64_t(get_d(a, "meta.seed"));
    c.batch_size = int(get_d(a, "meta.batch_size"));
  } catch (const Error&) {
    throw;
  } catch (const std::exception&) {
    throw Error(where, "model file lacks its metadata");
  }
  c.threads = threads;
  c.validate(where + ": metadata");
  auto s = std::make_unique<TorchSegmenter>(c);
  torch::serialize::InputArchive m;
  try {
    a.read("model", m);
  } catch (const std::exception& e) {
    throw Error(where, "model file lacks its weights: " + torch_reason(e));
  }
  load_weights(*s->impl_->net, m, where);
  return s;
}

namespace {
std::unique_ptr<detail::SegmenterBackend> create(const PointNetConfig& cfg) {
  return std::make_unique<TorchSegmenter>(cfg);
}
constexpr detail::BackendApi kApi{detail::kBackendApiVersion, &create, &TorchSegmenter::load};
}  // namespace

}  // namespace cropsight::nn

extern "C" __attribute__((visibility("default"))) const cropsight::nn::detail::BackendApi* cropsight_nn_backend() {
  return &cropsight::nn::kApi;
}
