// The plugin ABI (src/nn/segmenter_backend.hpp): libcropsight_nn_torch.so exports one symbol,
// the table through which nn::PointSegmenter creates and loads TorchSegmenters and nn::CenterNet
// its libtorch detectors.
#include "nn/torch/torch_detector.hpp"
#include "nn/torch/torch_segmenter.hpp"

namespace cropsight::nn {

namespace {
std::unique_ptr<detail::SegmenterBackend> create(const PointNetConfig& cfg) {
  return std::make_unique<TorchSegmenter>(cfg);
}
constexpr detail::BackendApi kApi{detail::kBackendApiVersion, &create, &TorchSegmenter::load,
                                  &torch_impl::create_detector, &torch_impl::load_detector};
}  // namespace

}  // namespace cropsight::nn

extern "C" __attribute__((visibility("default"))) const cropsight::nn::detail::BackendApi* cropsight_nn_backend() {
  return &cropsight::nn::kApi;
}
