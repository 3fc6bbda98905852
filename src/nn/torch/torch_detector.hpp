#pragma once
// The libtorch CenterNet behind nn::CenterNet (center_net_torch.cpp), exported through the
// plugin's table (plugin.cpp). No libtorch include here. Internal header of the plugin.
#include <filesystem>
#include <memory>

#include "nn/detector_backend.hpp"

namespace cropsight::nn::torch_impl {

std::unique_ptr<detail::DetectorBackend> create_detector(const CenterNetConfig& cfg);
std::unique_ptr<detail::DetectorBackend> load_detector(const std::filesystem::path& path, int threads);

// OpenBLAS single-threaded (torch_segmenter.cpp says why); both networks call it.
void single_threaded_blas();
// Sets the calling thread's libtorch operator threads to n (torch_segmenter.cpp); returns the
// count it had.
int set_operator_threads(int n);

}  // namespace cropsight::nn::torch_impl
