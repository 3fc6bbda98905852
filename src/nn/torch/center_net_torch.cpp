// The libtorch CenterNet (include/cropsight/nn/center_net.hpp says the design): the network, its
// losses, an Adam step, the eval-mode heads, model files and checkpoints. One translation unit on
// purpose: libtorch's headers cost ~17 s of a core per file (src/nn/CMakeLists.txt).
#include <torch/torch.h>

#include <dlfcn.h>

#include <exception>
#include <thread>
#include <type_traits>

#include "cropsight/core/error.hpp"
#include "cropsight/core/threads.hpp"
#include "nn/torch/archive.hpp"
#include "nn/torch/torch_detector.hpp"

namespace cropsight::nn::torch_impl {

// A named namespace (not an anonymous one): the plugin compiles as unity batches, where
// anonymous helpers of neighbouring files would collide.
namespace cnet {

namespace F = torch::nn::functional;

// Conv (no bias) + BatchNorm + optional ReLU: the one block of the backbone and the FPN.
struct ConvBnImpl : torch::nn::Module {
  torch::nn::Conv2d conv{nullptr};
  torch::nn::BatchNorm2d bn{nullptr};
  bool relu;
  ConvBnImpl(int in, int out, int k, int stride, bool relu_ = true) : relu(relu_) {
    conv = register_module(
        "conv", torch::nn::Conv2d(torch::nn::Conv2dOptions(in, out, k).stride(stride).padding(k / 2).bias(false)));
    bn = register_module("bn", torch::nn::BatchNorm2d(out));
  }
  torch::Tensor forward(const torch::Tensor& x) {
    auto y = bn(conv(x));
    return relu ? torch::relu(y) : y;
  }
};
TORCH_MODULE(ConvBn);

// A head: Conv-BN-ReLU 3x3, then a 1x1 conv with bias to the outputs.
struct HeadImpl : torch::nn::Module {
  ConvBn hidden{nullptr};
  torch::nn::Conv2d out{nullptr};
  HeadImpl(int in, int outs, double bias) {
    hidden = register_module("hidden", ConvBn(in, in, 3, 1));
    out = register_module("out", torch::nn::Conv2d(torch::nn::Conv2dOptions(in, outs, 1)));
    torch::nn::init::constant_(out->bias, bias);
  }
  torch::Tensor forward(const torch::Tensor& x) { return out(hidden(x)); }
};
TORCH_MODULE(Head);

struct NetImpl : torch::nn::Module {
  std::vector<ConvBn> stages;  // pairs (strided, plain) per stride 2, 4, 8, 16, 32
  ConvBn lat2{nullptr}, lat3{nullptr}, lat4{nullptr}, lat5{nullptr};
  ConvBn smooth2{nullptr}, smooth3{nullptr}, smooth4{nullptr};
  Head hm{nullptr}, wh{nullptr}, off{nullptr}, seg{nullptr};

  NetImpl(int w, int classes) {
    const int widths[5] = {w, 2 * w, 4 * w, 8 * w, 8 * w};
    int in = 3;
    for (int s = 0; s < 5; ++s) {
      stages.push_back(register_module("s" + std::to_string(s) + "a", ConvBn(in, widths[s], 3, 2)));
      stages.push_back(register_module("s" + std::to_string(s) + "b", ConvBn(widths[s], widths[s], 3, 1)));
      in = widths[s];
    }
    const int f = 2 * w;
    lat2 = register_module("lat2", ConvBn(widths[1], f, 1, 1));
    lat3 = register_module("lat3", ConvBn(widths[2], f, 1, 1));
    lat4 = register_module("lat4", ConvBn(widths[3], f, 1, 1));
    lat5 = register_module("lat5", ConvBn(widths[4], f, 1, 1));
    smooth2 = register_module("smooth2", ConvBn(f, f, 3, 1));
    smooth3 = register_module("smooth3", ConvBn(f, f, 3, 1));
    smooth4 = register_module("smooth4", ConvBn(f, f, 3, 1));
    // The heatmap bias starts at -2.19 (sigmoid 0.1: CenterNet's prior, which keeps the focal
    // loss of the many background cells from swamping the first steps).
    hm = register_module("hm", Head(f, classes, -2.19));
    wh = register_module("wh", Head(f, 2, 0.0));
    off = register_module("off", Head(f, 2, 0.0));
    seg = register_module("seg", Head(f, classes, -2.19));
  }

  static torch::Tensor up(const torch::Tensor& x) {
    return F::interpolate(
        x, F::InterpolateFuncOptions().scale_factor(std::vector<double>{2.0, 2.0}).mode(torch::kNearest));
  }

  // x (N, 3, H, W) → heatmap logits, size, offset, mask logits, each at stride 4.
  std::vector<torch::Tensor> forward(const torch::Tensor& x) {
    std::vector<torch::Tensor> c;
    torch::Tensor y = x;
    for (std::size_t s = 0; s < 5; ++s) {
      y = stages[2 * s + 1](stages[2 * s](y));
      c.push_back(y);
    }
    torch::Tensor p = lat5(c[4]);
    p = smooth4(up(p) + lat4(c[3]));
    p = smooth3(up(p) + lat3(c[2]));
    p = smooth2(up(p) + lat2(c[1]));
    return {hm(p), wh(p), off(p), seg(p)};
  }
};
TORCH_MODULE(Net);

// Penalty-reduced pixel-wise focal loss (CenterNet eq. 1, alpha 2, beta 4), normalised by the
// number of object centres.
torch::Tensor focal_loss(const torch::Tensor& logits, const torch::Tensor& gt) {
  const auto p = torch::sigmoid(logits).clamp(1e-4, 1 - 1e-4);
  const auto pos = gt.eq(1).to(torch::kFloat);
  const auto neg = 1 - pos;
  const auto pos_loss = (torch::log(p) * torch::pow(1 - p, 2) * pos).sum();
  const auto neg_loss = (torch::log(1 - p) * torch::pow(p, 2) * torch::pow(1 - gt, 4) * neg).sum();
  return -(pos_loss + neg_loss) / pos.sum().clamp_min(1);
}

// L1 of a 2-channel head at the object centres: pred (N, 2, H, W), index (N, K), target (N, K, 2),
// mask (N, K); normalised by the object count (times 2 channels), as CenterNet's RegL1Loss.
torch::Tensor reg_l1(const torch::Tensor& pred, const torch::Tensor& index, const torch::Tensor& target,
                     const torch::Tensor& mask) {
  const auto n = pred.size(0);
  const auto flat = pred.reshape({n, 2, -1});
  const auto idx = index.unsqueeze(1).expand({n, 2, index.size(1)});
  const auto got = flat.gather(2, idx).permute({0, 2, 1});  // (N, K, 2)
  const auto m = mask.unsqueeze(2).expand_as(got);
  return (torch::abs(got - target) * m).sum() / (m.sum() + 1e-4);
}

class Backend final : public detail::DetectorBackend {
 public:
  explicit Backend(const CenterNetConfig& c) : cfg_(c) {
    cfg_.validate("detector");
    at::set_num_threads(cfg_.threads);
    single_threaded_blas();
    torch::manual_seed(cfg_.seed);
    net_ = Net(cfg_.width, cfg_.num_classes());
    opt_ = std::make_unique<torch::optim::Adam>(net_->parameters(),
                                                torch::optim::AdamOptions(cfg_.lr).weight_decay(cfg_.weight_decay));
  }

  const CenterNetConfig& config() const override { return cfg_; }
  std::size_t parameter_count() const override {
    std::size_t n = 0;
    for (const auto& p : net_->parameters()) n += std::size_t(p.numel());
    return n;
  }
  void set_lr(double lr) override {
    for (auto& g : opt_->param_groups()) static_cast<torch::optim::AdamOptions&>(g.options()).lr(lr);
  }

  DetectorLosses train_step(const detail::DetectorBatch& b) override {
    const int64_t n = b.n, C = cfg_.num_classes(), H = cfg_.input_height, W = cfg_.input_width;
    const int64_t oh = H / 4, ow = W / 4, K = cfg_.max_objects;
    auto t = [](const std::vector<float>& v, std::vector<int64_t> shape) {
      return torch::from_blob(const_cast<float*>(v.data()), shape, torch::kFloat);
    };
    const auto images = t(b.images, {n, 3, H, W});
    const auto hm = t(b.heatmap, {n, C, oh, ow});
    const auto size = t(b.size, {n, K, 2}), offset = t(b.offset, {n, K, 2});
    const auto reg = t(b.reg_mask, {n, K});
    const auto index = torch::from_blob(const_cast<int64_t*>(b.index.data()), {n, K}, torch::kLong);
    net_->train();
    opt_->zero_grad();
    const auto out = net_->forward(images);
    const auto l_hm = focal_loss(out[0], hm);
    const auto l_wh = reg_l1(out[1], index, size, reg);
    const auto l_off = reg_l1(out[2], index, offset, reg);
    torch::Tensor l_seg = torch::zeros({});
    if (!b.mask.empty()) {
      const auto present = t(b.mask_present, {n});
      const auto bce =
          F::binary_cross_entropy_with_logits(out[3], t(b.mask, {n, C, oh, ow}),
                                              F::BinaryCrossEntropyWithLogitsFuncOptions().reduction(torch::kNone))
              .mean({1, 2, 3});
      l_seg = (bce * present).sum() / present.sum().clamp_min(1);
      if (cfg_.mask_dice_weight > 0) {  // soft Dice per class over the masked images of the batch
        const auto p = torch::sigmoid(out[3]) * present.view({n, 1, 1, 1});
        const auto target = t(b.mask, {n, C, oh, ow}) * present.view({n, 1, 1, 1});
        const auto inter = (p * target).sum({0, 2, 3});
        const auto dice = 1 - (2 * inter + 1) / (p.sum({0, 2, 3}) + target.sum({0, 2, 3}) + 1);
        l_seg = l_seg + cfg_.mask_dice_weight * dice.mean();
      }
    }
    const auto loss = l_hm + cfg_.size_weight * l_wh + cfg_.offset_weight * l_off + cfg_.mask_weight * l_seg;
    loss.backward();
    opt_->step();
    return {loss.item<double>(), l_hm.item<double>(), l_wh.item<double>(), l_off.item<double>(), l_seg.item<double>()};
  }

  // Eval-mode forward passes of a batch of n images: with several images (the flip test's image
  // and its mirror) and threads >= 2, each thread runs its share as an independent batch on one
  // OpenMP thread instead of all of them on one OpenMP team. A team's threads spin at every
  // layer's barrier; on a CPU busy with other work a descheduled member keeps the rest spinning
  // (308-532 ms an image instead of 48, docs/pipelines/detector.md), and OMP_WAIT_POLICY, which
  // would stop it, is read only when the process starts. Independent threads never wait for each
  // other until the final join, which sleeps.
  std::vector<CenterNetHeads> forward(const std::vector<float>& images, int n, int width, int height) const override {
    net_->eval();  // before the threads: it sets the modules' mode, which they then only read
    const int workers = std::min(n, cfg_.threads);
    if (workers < 2) return forward_batch(images.data(), n, width, height);
    const std::size_t per_image = 3 * std::size_t(width) * std::size_t(height);
    std::vector<std::vector<CenterNetHeads>> parts(static_cast<std::size_t>(workers));
    std::vector<std::exception_ptr> errors(static_cast<std::size_t>(workers));
    std::vector<std::thread> pool;
    struct JoinAll {  // a failed thread start must not leave started ones unjoined (terminate)
      std::vector<std::thread>& threads;
      ~JoinAll() {
        for (auto& t : threads)
          if (t.joinable()) t.join();
      }
    } join_all{pool};
    for (int w = 0; w < workers; ++w) {
      const int begin = w * n / workers, end = (w + 1) * n / workers;
      pool.emplace_back([&, w, begin, end] {
        try {
          one_openmp_thread();
          parts[std::size_t(w)] =
              forward_batch(images.data() + std::size_t(begin) * per_image, end - begin, width, height);
        } catch (...) {
          errors[std::size_t(w)] = std::current_exception();
        }
      });
    }
    for (auto& t : pool) t.join();
    std::vector<CenterNetHeads> heads;
    for (std::size_t w = 0; w < parts.size(); ++w) {
      if (errors[w]) std::rethrow_exception(errors[w]);
      for (auto& h : parts[w]) heads.push_back(std::move(h));
    }
    return heads;
  }

  void save(const std::filesystem::path& path) const override {
    torch::serialize::OutputArchive a, m;
    net_->save(m);
    a.write("model", m);
    a.write("meta.kind", c10::IValue(std::string(kKind)));
    CenterNetConfig c = cfg_;
    PutMeta put{a};
    c.visit(put);
    save_archive_atomic(a, path);
  }

  void set_inference(const CenterNetConfig& c) override {
    cfg_.input_width = c.input_width;
    cfg_.input_height = c.input_height;
    cfg_.mask_thresholds = c.mask_thresholds;
    cfg_.mask_upsampling = c.mask_upsampling;
    cfg_.flip_test = c.flip_test;
    cfg_.mask_inputs = c.mask_inputs;
    cfg_.mask_inputs_flip_test = c.mask_inputs_flip_test;
  }

  std::vector<detail::FoldedConv> folded_convs() const override {
    torch::NoGradGuard no_grad;
    std::vector<detail::FoldedConv> out;
    auto vec = [](const torch::Tensor& t) {
      const auto c = t.contiguous();
      return std::vector<float>(c.data_ptr<float>(), c.data_ptr<float>() + c.numel());
    };
    auto fold = [&](const std::string& name, ConvBn& m) {
      const auto& bn = m->bn;
      const auto g = bn->weight / torch::sqrt(bn->running_var + bn->options.eps());
      const auto w = m->conv->weight * g.reshape({-1, 1, 1, 1});
      const auto b = bn->bias - bn->running_mean * g;
      out.push_back({name, int(w.size(0)), int(w.size(1)), int(w.size(2)), int(m->conv->options.stride()->at(0)),
                     m->relu, vec(w), vec(b)});
    };
    for (std::size_t s = 0; s < 5; ++s) {
      fold("s" + std::to_string(s) + "a", net_->stages[2 * s]);
      fold("s" + std::to_string(s) + "b", net_->stages[2 * s + 1]);
    }
    fold("lat2", net_->lat2), fold("lat3", net_->lat3), fold("lat4", net_->lat4), fold("lat5", net_->lat5);
    fold("smooth2", net_->smooth2), fold("smooth3", net_->smooth3), fold("smooth4", net_->smooth4);
    for (auto [name, head] : {std::pair{"hm", net_->hm}, {"wh", net_->wh}, {"off", net_->off}, {"seg", net_->seg}}) {
      fold(std::string(name) + ".hidden", head->hidden);
      const auto& c = head->out;
      out.push_back({std::string(name) + ".out", int(c->weight.size(0)), int(c->weight.size(1)), 1, 1, false,
                     vec(c->weight), vec(c->bias)});
    }
    return out;
  }

  void write_checkpoint(const std::filesystem::path& path, int epochs_done) const override {
    torch_impl::write_checkpoint(path, *net_, *opt_, epochs_done);
  }
  int read_checkpoint(const std::filesystem::path& path) override {
    return torch_impl::read_checkpoint(path.string(), *net_, *opt_);
  }

  static std::unique_ptr<detail::DetectorBackend> load(const std::filesystem::path& path, int threads) {
    const std::string where = path.string();
    check_thread_count(threads, "threads");
    torch::serialize::InputArchive a;
    open_model_archive(a, path, "detector");
    CenterNetConfig c;
    c.mask_upsampling = "nearest";  // what a model written before the key was calibrated for
    try {
      c10::IValue kind;
      a.read("meta.kind", kind);
      if (kind.toStringRef() != kKind)
        throw Error(where, "not a cropsight detector model (kind " + kind.toStringRef() + ")");
      GetMeta get{a};
      c.visit(get);
    } catch (const Error&) {
      throw;
    } catch (const std::exception&) {
      throw Error(where, "not a cropsight detector model (no detector metadata)");
    }
    c.threads = threads;
    c.validate(where + ": metadata");
    auto b = std::make_unique<Backend>(c);
    read_model_weights(a, *b->net_, where);
    return b;
  }

 private:
  static constexpr const char* kKind = "cropsight-centernet";

  // The configuration as archive metadata, one entry per visit() key: strings as strings,
  // numbers as doubles (every field is an int, a double or a small seed).
  struct PutMeta {
    torch::serialize::OutputArchive& a;
    template <class T>
    void operator()(const char* k, T& f, const char*, const Range& = {}) {
      if constexpr (std::is_same_v<T, std::string>)
        a.write(std::string("meta.") + k, c10::IValue(f));
      else
        a.write(std::string("meta.") + k, c10::IValue(double(f)));
    }
  };
  // A key the archive lacks keeps its default only where a later version added it (a model
  // written before mask_thresholds, mask_upsampling, flip_test, mask_inputs or mask_dice_weight existed); any other
  // missing key is not a cropsight model.
  struct GetMeta {
    torch::serialize::InputArchive& a;
    template <class T>
    void operator()(const char* k, T& f, const char*, const Range& = {}) {
      c10::IValue v;
      if (std::string(k) == "mask_thresholds" || std::string(k) == "mask_upsampling" || std::string(k) == "flip_test" ||
          std::string(k) == "mask_inputs" || std::string(k) == "mask_inputs_flip_test" ||
          std::string(k) == "mask_dice_weight") {
        if (!a.try_read(std::string("meta.") + k, v)) return;
      } else {
        a.read(std::string("meta.") + k, v);
      }
      if constexpr (std::is_same_v<T, std::string>)
        f = v.toStringRef();
      else
        f = T(v.toDouble());
    }
  };

  CenterNetConfig cfg_;
  // This thread's ATen parallel regions on one OpenMP thread: ATen sets a new thread's OpenMP
  // thread count on its first parallel call (get_num_threads does it), then omp_set_num_threads
  // overrides it for this thread alone (the symbol is libgomp's, loaded with libtorch).
  static void one_openmp_thread() {
    at::get_num_threads();
    using SetThreads = void (*)(int);
    if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "omp_set_num_threads"))) set(1);
  }

  // The heads of n images of width x height pixels at `images` (one batch).
  std::vector<CenterNetHeads> forward_batch(const float* images, int n, int width, int height) const {
    torch::NoGradGuard no_grad;
    const int64_t H = height, W = width;
    const auto x = torch::from_blob(const_cast<float*>(images), {n, 3, H, W}, torch::kFloat);
    auto out = net_->forward(x);
    out[0] = torch::sigmoid(out[0]);
    out[3] = torch::sigmoid(out[3]);
    std::vector<CenterNetHeads> heads(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      auto& h = heads[std::size_t(i)];
      h.classes = cfg_.num_classes(), h.out_h = int(H / 4), h.out_w = int(W / 4);
      auto copy = [&](const torch::Tensor& t, std::vector<float>& v) {
        const auto c = t[i].contiguous();
        v.assign(c.data_ptr<float>(), c.data_ptr<float>() + c.numel());
      };
      copy(out[0], h.heatmap), copy(out[1], h.size), copy(out[2], h.offset), copy(out[3], h.mask);
    }
    return heads;
  }

  mutable Net net_{nullptr};  // eval-mode forward passes from const methods
  std::unique_ptr<torch::optim::Adam> opt_;
};

}  // namespace cnet

std::unique_ptr<detail::DetectorBackend> create_detector(const CenterNetConfig& cfg) {
  return std::make_unique<cnet::Backend>(cfg);
}
std::unique_ptr<detail::DetectorBackend> load_detector(const std::filesystem::path& path, int threads) {
  return cnet::Backend::load(path, threads);
}

}  // namespace cropsight::nn::torch_impl
