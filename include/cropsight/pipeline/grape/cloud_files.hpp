#pragma once
// Cloud files for the grape segmenter (segment grape): which files a user named, each read as a
// segmentation model sees it, and the labelled cloud written back in the file's own coordinates.
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"
#include "cropsight/pipeline/grape/roi.hpp"

namespace cropsight::pipeline::grape {

/// The cloud files `spec` names: one file, a folder (its .txt, .ply and .pcd files in name order;
/// those of its points/ subfolder when it has one, the dataset's layout) or a comma-separated list
/// of either. Throws Error naming the entry that is neither.
std::vector<std::filesystem::path> list_cloud_files(const std::string& spec);

/// One cloud file: what the model reads and what is written back.
struct SegmentInput {
  Cloud model_view;  ///< unit sphere, normals, colours in [0, 1]
  Cloud original;    ///< the file's points (and normals, colours) as they were
};

/// Reads one cloud for a segmentation model. The dataset's text format (.txt: x y z nx ny nz r g b
/// label, already at unit scale) is read as it is; a PLY or PCD (metres, camera frame, as
/// `detect grape` and `roi-cloud` write them) is made ready as the pipeline readies its ROI clouds
/// (segmenter_input: KNN-PCA normals where the file has none, unit-sphere scale). Throws
/// Error(path, ...) for an unreadable file, one without colours (the models read r g b) or with
/// fewer than 3 points.
SegmentInput read_segment_input(const std::filesystem::path& path, const RoiConfig& cfg = {});

/// Reads one labelled cloud as the trainers and evaluators read it: the model's view of the file
/// (read_segment_input) with the file's own labels, so that a PLY or PCD written by `segment
/// grape` or `detect grape` and corrected in a point-cloud editor (CloudCompare and the like keep
/// an integer `label` field) trains a model. Throws Error(path, ...) as read_segment_input, and
/// for a PLY or PCD without a label per point.
Cloud read_labelled_cloud(const std::filesystem::path& path, const RoiConfig& cfg = {});

/// Writes `cloud` with its labels, the format by extension: .txt the dataset's text format, .ply
/// or .pcd through PCL with an int32 `label` field. Atomic (temporary name, then rename).
void write_labelled_cloud(const std::filesystem::path& path, const Cloud& cloud);

}  // namespace cropsight::pipeline::grape
