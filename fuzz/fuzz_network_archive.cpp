// libFuzzer harness: network archives (libtorch .pt files written by `train grape`
// and `train detector`) through the plugin's loader: nn::PointSegmenter::load and
// nn::CenterNet::load, which dlopen libcropsight_nn_torch.so. Clang cannot compile libtorch's
// headers as C++20, so the fuzz build has no plugin of its own: scripts/fuzz.sh points
// $CROPSIGHT_NN_BACKEND at the regular (GCC) build's plugin. That plugin is not instrumented, so
// libFuzzer's coverage stops at our side of the interface; crashes, aborts and escaped exceptions
// inside it are still caught.
#include "cropsight/nn/center_net.hpp"
#include "cropsight/nn/point_segmenter.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cropsight::fuzz::write_input(data, size, "model.pt");
  cropsight::fuzz::expect_error_or_success("PointSegmenter::load",
                                           [&] { (void)cropsight::nn::PointSegmenter::load(path, 1); });
  cropsight::fuzz::expect_error_or_success("CenterNet::load", [&] { (void)cropsight::nn::CenterNet::load(path, 1); });
  return 0;
}
