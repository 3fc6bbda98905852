#pragma once
// libtorch archives: model files, training checkpoints, and the shape-checked weight loading
// both need. Internal header of the libtorch plugin (src/nn/torch/ only).
#include <torch/torch.h>

#include <exception>
#include <filesystem>
#include <string>

namespace cropsight::nn::torch_impl {

// libtorch's messages carry a multi-line C++ stack trace: the first line is the reason.
std::string torch_reason(const std::exception& e);

// Writes `a` to `path` through io::write_atomic_with (temporary sibling, then rename; removed on
// any failure), with libtorch's error reduced to one line.
void save_archive_atomic(torch::serialize::OutputArchive& a, const std::filesystem::path& path);

// Loads `net`'s weights from `a`, checking that every tensor keeps its shape: libtorch's
// Module::load swaps in tensors of any shape (a checkpoint of another width or feature set would
// load, then crash in the first forward pass). Throws Error(where, ...).
void load_weights(torch::nn::Module& net, torch::serialize::InputArchive& a, const std::string& where);

// Opens the model file `path` into `a`. Error(path, ...) when it is missing, a directory, or no
// libtorch archive ("not a cropsight <what> model: <reason>").
void open_model_archive(torch::serialize::InputArchive& a, const std::filesystem::path& path, const std::string& what);
// The "model" entry of a model file into `net` (load_weights' shape checks). Error(where, ...).
void read_model_weights(torch::serialize::InputArchive& a, torch::nn::Module& net, const std::string& where);

// A training checkpoint at `path`: the weights, the optimiser state and the epochs done.
void write_checkpoint(const std::filesystem::path& path, const torch::nn::Module& net,
                      const torch::optim::Optimizer& opt, int epochs_done);
// Restores `net` and `opt` from the checkpoint `where` and returns its epochs done. A bad
// checkpoint is the user's file: Error(where, ...) names it, with libtorch's one-line reason.
int read_checkpoint(const std::string& where, torch::nn::Module& net, torch::optim::Optimizer& opt);

}  // namespace cropsight::nn::torch_impl
