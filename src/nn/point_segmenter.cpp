// nn::PointSegmenter: forwards to the libtorch backend plugin (segmenter_backend.hpp), which it
// loads on first use. Nothing here includes or links libtorch.
#include "cropsight/nn/point_segmenter.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/core/install_paths.hpp"
#include "nn/segmenter_backend.hpp"

namespace cropsight::nn {

namespace {

// Where the plugin may be, in order: $CROPSIGHT_NN_BACKEND (a file), beside the program's lib/
// (an install or a build tree: bin/cropsight and lib/libcropsight_nn_torch.so), beside the
// program, then the loader's own search path (LD_LIBRARY_PATH, ...). No build-tree path is
// compiled in: an install moved elsewhere finds its plugin the same way.
std::vector<std::string> candidates() {
  std::vector<std::string> out;
  if (const char* env = std::getenv("CROPSIGHT_NN_BACKEND"); env && *env) return {env};
  const auto dir = executable_dir();
  if (!dir.empty()) {
    out.push_back((dir / ".." / "lib" / detail::kBackendFile).string());
    out.push_back((dir / detail::kBackendFile).string());
  }
  out.push_back(detail::kBackendFile);
  return out;
}

const detail::BackendApi* load_backend() {
  std::string tried, last_error;
  for (const auto& file : candidates()) {
    const bool bare = file.find('/') == std::string::npos;
    if (!bare && !std::filesystem::exists(file)) {
      tried += (tried.empty() ? "" : ", ") + file;
      continue;
    }
    // RTLD_GLOBAL: the backend looks OpenBLAS up by name (single-threaded BLAS, torch_segmenter.cpp).
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (!handle) {
      const char* e = dlerror();
      last_error = e ? e : "unknown error";
      tried += (tried.empty() ? "" : ", ") + file;
      continue;
    }
    // The handle is never closed: the process keeps the backend (and libtorch) once loaded.
    using Entry = const detail::BackendApi* (*)();
    auto entry = reinterpret_cast<Entry>(dlsym(handle, detail::kBackendEntry));
    const detail::BackendApi* api = entry ? entry() : nullptr;
    if (!api || api->version != detail::kBackendApiVersion || !api->create || !api->load || !api->create_detector ||
        !api->load_detector)
      throw Error(file, "not a cropsight network backend of this version (rebuild cropsight)");
    return api;
  }
  throw Error("network backend", "cannot load " + std::string(detail::kBackendFile) + " (tried " + tried +
                                     (last_error.empty() ? "" : "; " + last_error) +
                                     "); set CROPSIGHT_NN_BACKEND to its path");
}

}  // namespace

// Loaded once per process, on the first network built or loaded (a throwing first attempt is
// retried by the next call); initialisation of a function-local static is thread-safe.
const detail::BackendApi& detail::backend_api() {
  static const detail::BackendApi* api = load_backend();
  return *api;
}

namespace {
const detail::BackendApi& backend() { return detail::backend_api(); }
}  // namespace

struct PointSegmenter::Impl {
  std::unique_ptr<detail::SegmenterBackend> backend;
};

PointSegmenter::PointSegmenter(const PointNetConfig& cfg) : impl_(std::make_unique<Impl>()) {
  cfg.validate("point network");  // before the plugin: a bad config is named even without it
  impl_->backend = backend().create(cfg);
}
PointSegmenter::PointSegmenter() = default;
PointSegmenter::~PointSegmenter() = default;
PointSegmenter::PointSegmenter(PointSegmenter&&) noexcept = default;
PointSegmenter& PointSegmenter::operator=(PointSegmenter&&) noexcept = default;

const PointNetConfig& PointSegmenter::config() const { return impl_->backend->config(); }
std::size_t PointSegmenter::parameter_count() const { return impl_->backend->parameter_count(); }
std::pair<double, double> PointSegmenter::train_step(const std::vector<Cloud>& batch) {
  return impl_->backend->train_step(batch);
}
std::vector<EpochLog> PointSegmenter::train(const std::vector<Cloud>& train, const std::vector<Cloud>& val,
                                            const std::function<void(const EpochLog&)>& on_epoch) {
  return impl_->backend->train(train, val, on_epoch);
}
std::vector<int> PointSegmenter::segment(const Cloud& cloud, int* passes_out, int votes,
                                         std::vector<float>* proba) const {
  return impl_->backend->segment(cloud, passes_out, votes, proba);
}
std::vector<int> PointSegmenter::segment_sampled(const Cloud& cloud, bool farthest) const {
  return impl_->backend->segment_sampled(cloud, farthest);
}
std::vector<int> PointSegmenter::sample_for_pass(const Cloud& cloud, bool farthest, int pass) const {
  return impl_->backend->sample_for_pass(cloud, farthest, pass);
}
std::vector<int> PointSegmenter::predict_at(const Cloud& cloud, const std::vector<int>& idx, float angle_rad,
                                            std::vector<float>* proba) const {
  return impl_->backend->predict_at(cloud, idx, angle_rad, proba);
}
std::vector<std::vector<int>> PointSegmenter::predict_passes(const Cloud& cloud,
                                                             const std::vector<std::vector<int>>& idx,
                                                             const std::vector<float>& angle_rad, int threads,
                                                             std::vector<std::vector<float>>* proba) const {
  return impl_->backend->predict_passes(cloud, idx, angle_rad, threads, proba);
}
void PointSegmenter::save(const std::filesystem::path& path) const { impl_->backend->save(path); }

PointSegmenter PointSegmenter::load(const std::filesystem::path& path, int threads) {
  PointSegmenter s;
  s.impl_ = std::make_unique<Impl>();
  s.impl_->backend = backend().load(path, threads);
  return s;
}

}  // namespace cropsight::nn
