#pragma once
// The labels a studio writes for a folder of images (cropsight studio --images DIR): boxes and
// polygons with classes, in the three forms detectors are trained from. The image folder itself
// is never written to except for one clearly named subfolder, DIR/cropsight-labels/:
//
//   coco.json          COCO instances of every labelled image (file_name relative to DIR); what
//                      `train detector --coco` and `import` read; the studio reads it back on start
//   voc/STEM.xml       one Pascal VOC file per labelled image (boxes; a polygon as its bounds)
//   yolo/STEM.txt      one YOLO txt per labelled image ("class cx cy w h", normalised)
//   yolo/classes.txt   the class names, line k = YOLO class k (classes are only ever appended)
//   .cropsight-output  the output marker (io/output.hpp) listing every file above
//
// A labelled image is one saved at least once, with or without shapes (an image without potatoes
// is a label too). Labels of an image that is no longer in the folder stay in coco.json.
//
// The subfolder must be new or one a studio wrote (its marker names "studio"): anything else at
// that name is refused, and so is any file in it the marker does not list, so a user's own file
// is never replaced. Every file is written under a temporary name and renamed (io/files.hpp);
// coco.json last, so a kill leaves the previous coco.json with per-image files that may be one
// save newer (the next save of that image rewrites them).
//
// Thread-safe: every call takes the store's mutex (the server answers on several threads).
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cropsight/io/image_labels.hpp"

namespace cropsight::studio {

/// The subfolder of the image folder that holds the studio's label files.
inline constexpr const char* kImageLabelsFolder = "cropsight-labels";

class ImageLabelStore {
 public:
  /// The images of `dir` (.jpg, .jpeg, .png in name order; not hidden ones, nor symbolic links
  /// that lead out of `dir`) and the labels the studio saved there
  /// before. `classes`: class names to offer first (the model's). Throws Error naming the folder
  /// or file: no image, two images with one stem (their VOC and YOLO files would collide), a
  /// cropsight-labels that no studio wrote, or a coco.json that cannot be read.
  ImageLabelStore(std::filesystem::path dir, const std::vector<std::string>& classes, bool read_only);

  const std::filesystem::path& folder() const { return dir_; }
  std::filesystem::path output_folder() const { return dir_ / kImageLabelsFolder; }
  /// Image file names (relative to the folder), in name order; an image's index is its position.
  const std::vector<std::string>& images() const { return names_; }
  /// The image file of `index` (0 <= index < images().size()).
  std::filesystem::path image_path(int index) const { return dir_ / names_.at(std::size_t(index)); }
  /// Indices of the labelled images, ascending.
  std::vector<int> labelled() const;
  /// Class names: the model's, then those of saved labels in order of first use.
  std::vector<std::string> classes() const;
  /// The saved labels of `index`, or nothing when it is not labelled.
  std::optional<io::ImageLabels> labels(int index) const;
  /// The image's width and height in pixels (read from the file once, then remembered). Throws
  /// Error naming the file when it cannot be decoded.
  std::pair<int, int> size(int index);
  /// Writes `index`'s shapes (pixels of its image) into every output form. Throws Error when
  /// read-only, when a file to write is one the studio did not write, or on a write failure.
  void save(int index, std::vector<io::LabelShape> shapes);

 private:
  void write_outputs(int index);

  std::filesystem::path dir_;
  std::vector<std::string> names_;
  bool read_only_ = false;
  mutable std::mutex mutex_;
  std::vector<std::string> classes_;
  std::map<std::string, io::ImageLabels> saved_;  // by file name
  std::vector<std::string> written_;              // what the marker lists
  std::map<int, std::pair<int, int>> sizes_;
};

}  // namespace cropsight::studio
