#include "cropsight/pipeline/grape/cloud_files.hpp"

#include "cropsight/core/error.hpp"
#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/file_names.hpp"
#include "cropsight/io/grape_text.hpp"

namespace cropsight::pipeline::grape {

namespace fs = std::filesystem;

namespace {
const std::vector<std::string> kCloudExtensions = {".txt", ".ply", ".pcd"};
}  // namespace

std::vector<fs::path> list_cloud_files(const std::string& spec) {
  std::vector<fs::path> out;
  std::size_t start = 0;
  while (start <= spec.size()) {
    const std::size_t comma = std::min(spec.find(',', start), spec.size());
    const std::string entry = spec.substr(start, comma - start);
    if (entry.empty()) throw Error("--clouds", "empty entry in the list '" + spec + "'");
    // The dataset's layout keeps a folder's clouds under points/ (io::list_grape_clouds reads it too).
    std::error_code ec;
    const fs::path folder =
        fs::is_directory(fs::path(entry) / "points", ec) ? fs::path(entry) / "points" : fs::path(entry);
    for (fs::path& p : io::list_files_with(folder, kCloudExtensions, ".txt, .ply or .pcd cloud")) out.push_back(p);
    start = comma + 1;
  }
  return out;
}

SegmentInput read_segment_input(const fs::path& path, const RoiConfig& cfg) {
  SegmentInput in;
  if (io::lower_extension(path) == ".txt") {
    in.model_view = io::read_grape_text(path);
    in.original = in.model_view;
    return in;
  }
  in.original = io::read_cloud(path);
  if (in.original.size() < 3)
    throw Error(path.string(), "has " + std::to_string(in.original.size()) + " points; a cloud to label needs 3");
  if (!in.original.has_colors()) throw Error(path.string(), "has no colours (rgb): the grape models read r g b");
  Cloud metric = in.original;
  metric.labels.clear();
  in.model_view = segmenter_input(std::move(metric), cfg).cloud;
  return in;
}

Cloud read_labelled_cloud(const fs::path& path, const RoiConfig& cfg) {
  SegmentInput in = read_segment_input(path, cfg);
  if (io::lower_extension(path) == ".txt") return std::move(in.model_view);  // labels in the text
  if (in.original.labels.size() != in.original.size())
    throw Error(path.string(), "has no label field: a training or evaluation cloud needs one label per point");
  in.model_view.labels = std::move(in.original.labels);  // segmenter_input keeps the point order
  return std::move(in.model_view);
}

void write_labelled_cloud(const fs::path& path, const Cloud& cloud) {
  if (io::lower_extension(path) == ".txt")
    io::write_grape_text(path, cloud);
  else
    io::write_cloud(path, cloud);
}

}  // namespace cropsight::pipeline::grape
