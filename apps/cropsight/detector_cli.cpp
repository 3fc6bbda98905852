// The detector commands' shared options (detector_cli.hpp).
#include "detector_cli.hpp"

#include <cmath>
#include <cstdio>

#include "cli_common.hpp"
#include "cropsight/core/error.hpp"

namespace cropsight::cli {

void add_dataset_options(CLI::App* cmd, DatasetOptions& o) {
  cmd->add_option("--coco", o.coco, "COCO instance annotations (JSON: images, annotations, categories)");
  cmd->add_option("--voc", o.voc, "Folder of Pascal VOC .xml annotations");
  cmd->add_option("--images", o.images, "Folder of the images the annotations name")->required();
  cmd->add_option("--classes", o.classes,
                  "Comma-separated class names, in class-id order (VOC: required; COCO: default every category)");
}

nn::DetectionDataset load_dataset(const DatasetOptions& o) {
  if (o.coco.empty() == o.voc.empty()) throw Error("--coco/--voc", "give exactly one of --coco ANN.json and --voc DIR");
  const std::vector<std::string> classes =
      o.classes.empty() ? std::vector<std::string>{} : split_list(o.classes, "--classes");
  auto set = o.coco.empty() ? nn::read_voc_detection(o.voc, o.images, classes)
                            : nn::read_coco_detection(o.coco, o.images, classes);
  if (set.samples.empty()) throw Error(o.coco.empty() ? o.voc : o.coco, "names no image");
  return set;
}

std::pair<int, int> parse_input_size(const std::string& text) {
  int w = 0, h = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x')
    throw Error("--input-size", "expects WxH, e.g. 416x416, got '" + text + "'");
  return {w, h};
}

std::string input_size_text(const nn::CenterNetConfig& cfg) {
  return std::to_string(cfg.input_width) + "x" + std::to_string(cfg.input_height);
}

std::vector<double> rounded_thresholds(const std::vector<float>& t) {
  std::vector<double> out;
  for (float v : t) out.push_back(std::round(double(v) * 1e4) / 1e4);
  return out;
}

}  // namespace cropsight::cli
