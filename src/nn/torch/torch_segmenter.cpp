// TorchSegmenter's construction: the network of the configuration, libtorch's and OpenBLAS's
// thread counts.
#include "nn/torch/torch_segmenter.hpp"

#include <dlfcn.h>

#include "nn/torch/segmenter_impl.hpp"
#include "nn/torch/torch_detector.hpp"

namespace cropsight::nn {

// Debian's libtorch does its GEMMs in OpenBLAS, whose own pthread pool (one worker per core,
// spinning while it waits) made a training epoch of the CPU-sized networks 2.2x slower on two
// cores (3.0-3.5 s vs 1.4 s per epoch with identical losses, --threads 1 or 2): these GEMMs are
// small, and torch's intra-op threads (--threads) already parallelise the work. So OpenBLAS runs
// single-threaded; looked up at run time because a libtorch built on another BLAS lacks it.
void torch_impl::single_threaded_blas() {
  using SetThreads = void (*)(int);
  if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) set(1);
}

TorchSegmenter::Impl::Impl(const PointNetConfig& c) : cfg(c) {
  cfg.validate("point network");
  at::set_num_threads(cfg.threads);
  torch_impl::single_threaded_blas();
  torch::manual_seed(cfg.seed);
  net = torch_impl::SegNet(cfg);
  class_weights = torch::ones({cfg.num_classes});
}

TorchSegmenter::TorchSegmenter(const PointNetConfig& cfg) : impl_(std::make_unique<Impl>(cfg)) {}
TorchSegmenter::~TorchSegmenter() = default;
const PointNetConfig& TorchSegmenter::config() const { return impl_->cfg; }

std::size_t TorchSegmenter::parameter_count() const {
  std::size_t n = 0;
  for (const auto& p : impl_->net->parameters()) n += std::size_t(p.numel());
  return n;
}

}  // namespace cropsight::nn
