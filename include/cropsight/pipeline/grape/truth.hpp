#pragma once
// Ground truth of the grape pipeline: labelled ROI clouds in the authors' text format
// (io::read_grape_text: x y z nx ny nz r g b label per line, docs/formats.md) and the label ids
// they use. Boxes given as COCO files are read by read_coco_detections (roi.hpp).
#include <filesystem>
#include <vector>

#include "cropsight/core/cloud.hpp"

namespace cropsight::pipeline::grape {

/// The paper's classes as the dataset's label ids: 1 grape, 2 peduncle, 3 leaf, 4 background,
/// 5 noise (label 0 left out, see above).
inline const std::vector<int>& grape_named_classes() {
  static const std::vector<int> classes = {1, 2, 3, 4, 5};
  return classes;
}

/// Points per label 0-5 of `cloud` (a label outside them is not counted): the dataset's six labels
/// in id order, as a segmenter or the truth gives them.
std::vector<long> label_counts(const Cloud& cloud);

/// Loads every labelled cloud of `files` (the dataset's text clouds, or PLY / PCD with a label
/// field: read_labelled_cloud); throws Error(file, ...).
std::vector<Cloud> load_grape_clouds(const std::vector<std::filesystem::path>& files);

}  // namespace cropsight::pipeline::grape
