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

// libtorch's operators split their loops over OpenMP threads, as many as the calling thread's
// OpenMP setting allows; a thread libtorch has not seen starts at every core (two pass workers
// would start four threads on two cores). So a pass worker sets its own count to 1. libtorch
// sets a thread's count from the process-wide one on its first use, so that comes first
// (at::get_num_threads); at::set_num_threads would change the process-wide count for every
// thread, hence OpenMP's per-thread call, looked up at run time like OpenBLAS's above.
int torch_impl::set_operator_threads(int n) {
  const int before = at::get_num_threads();
  using SetThreads = void (*)(int);
  if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "omp_set_num_threads"))) set(n);
  return before;
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
