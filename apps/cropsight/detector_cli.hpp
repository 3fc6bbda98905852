#pragma once
// What the detector commands (train / eval / detect objects) share: the labelled-set options
// (--coco ANN.json | --voc DIR, --images DIR, --classes a,b) and the held-out split.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cropsight/nn/center_net.hpp"
#include "cropsight/nn/detection_dataset.hpp"

namespace cropsight::cli {

struct DatasetOptions {
  std::string coco, voc, images, classes;
};

/// Adds --coco, --voc, --images and --classes to `cmd`.
void add_dataset_options(CLI::App* cmd, DatasetOptions& o);

/// Reads the set the options name (exactly one of --coco and --voc). Throws Error naming the
/// option or file.
nn::DetectionDataset load_dataset(const DatasetOptions& o);

/// A held-out split: round(fraction * n) images (at least one when fraction > 0 and n >= 2) drawn
/// with `seed`, the others train. Indices in increasing order.
struct Split {
  std::vector<std::size_t> train, val;
};
Split split_indices(std::size_t n, double fraction, std::uint64_t seed);

/// Per-class mask thresholds chosen on `train` (nn::calibrate_mask_thresholds), set on `net`;
/// returns them (empty, and nothing set, when no training image has masks).
/// "WxH" (e.g. 416x416) as {W, H}; throws Error("--input", ...) for another form.
std::pair<int, int> parse_input_size(const std::string& text);
/// The model's input size as "WxH", the form parse_input_size reads.
std::string input_size_text(const nn::CenterNetConfig& cfg);

std::vector<float> calibrate_masks(nn::CenterNet& net, const std::vector<nn::DetectionSample>& train);

/// Mask thresholds as JSON numbers rounded to 1e-4 (0.65, not 0.6500000357627869).
std::vector<double> rounded_thresholds(const std::vector<float>& t);

}  // namespace cropsight::cli
