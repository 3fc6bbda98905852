#pragma once
// What the detector commands (train / eval / detect objects) share: the labelled-set options
// (--coco ANN.json | --voc DIR, --images DIR, --classes a,b), the input size and the thresholds'
// JSON form. The held-out split is the library's (nn::split_detection_set).
#include <CLI/CLI.hpp>
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

/// "WxH" (e.g. 416x416) as {W, H}; throws Error("--input", ...) for another form.
std::pair<int, int> parse_input_size(const std::string& text);
/// The model's input size as "WxH", the form parse_input_size reads.
std::string input_size_text(const nn::CenterNetConfig& cfg);

/// Mask thresholds as JSON numbers rounded to 1e-4 (0.65, not 0.6500000357627869).
std::vector<double> rounded_thresholds(const std::vector<float>& t);

}  // namespace cropsight::cli
