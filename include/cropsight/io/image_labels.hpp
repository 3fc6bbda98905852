#pragma once
// Labels drawn on images by other tools, read into one form and written back in the forms our
// trainers read (docs/formats.md, "Image labels"):
//
//   read:  COCO instances JSON (bbox, polygon segmentation), a labelme folder (one JSON per image:
//          rectangle and polygon shapes), CVAT for images 1.1 XML (<box>, <polygon>)
//   write: COCO instances JSON (what `train detector --coco` and `detect objects --coco` read),
//          YOLO txt (one file per image: "class cx cy w h", normalised to the image size), Pascal
//          VOC XML (one file per image), and, for a depth sequence, instance label PNGs
//          (rasterise_instances; io/sequence.hpp writes them as the simulator does).
//
// Units: image pixels with continuous corners (a box [x1, y1, x2, y2] covers x1 <= x < x2); a
// polygon's vertices are pixel coordinates as the tool wrote them. Every reader checks what it
// reads and throws Error(file, "what: problem") naming the key, element or shape.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/core/image.hpp"
#include "cropsight/io/output.hpp"

namespace cropsight::io {

/// One labelled object: a box, or a polygon of one or more parts (an object a leaf cuts in two;
/// its box then bounds every vertex).
struct LabelShape {
  std::string label;
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;               ///< pixels; x2 >= x1, y2 >= y1
  std::vector<std::vector<Eigen::Vector2d>> polygons;  ///< empty for a box; else parts of >= 3 vertices
};

/// The shapes of one image.
struct ImageLabels {
  std::string file_name;  ///< as the tool recorded it (may hold folders)
  int width = 0, height = 0;
  std::vector<LabelShape> shapes;
};

/// Labels of an image set and the class names in the order they were first met (COCO: by
/// category id).
struct LabelSet {
  std::vector<std::string> classes;
  std::vector<ImageLabels> images;
};

LabelSet read_coco_labels(const std::filesystem::path& file);
/// Every *.json of `dir` (name order) is one labelme file; "imagePath", "imageWidth/Height", "shapes"
/// with shape_type rectangle or polygon (others are refused, naming the shape).
LabelSet read_labelme_labels(const std::filesystem::path& dir);
LabelSet read_cvat_labels(const std::filesystem::path& file);

/// The COCO instances JSON of `set`: images (ids from 1 in order), categories (ids from 1 in
/// classes order), annotations with bbox [x, y, w, h], area and, for polygons, segmentation.
std::string coco_json(const LabelSet& set);
/// One YOLO line per shape: class index (in set.classes), box centre and size over the image size.
std::string yolo_text(const ImageLabels& image, const std::vector<std::string>& classes);
/// One Pascal VOC <annotation> (as io/voc.hpp reads it back).
std::string voc_xml(const ImageLabels& image);

/// The instance label image of `image` (width × height): shape k's pixels hold first_id + k, 0
/// elsewhere; where shapes overlap, the later one wins. Polygons are filled (even-odd), boxes whole.
LabelImage rasterise_instances(const ImageLabels& image, int first_id);

/// The frame index a sequence frame's file name carries ("color/000012.png", "frame_12.jpg" → 12):
/// the last run of digits of its stem; -1 when it has none.
int frame_index_from_name(const std::string& file_name);

/// What write_labelled_sequence wrote.
struct LabelledSequenceSummary {
  int frames = 0;                  ///< frames written (those the labels name)
  int instances = 0;               ///< shapes rasterised into them
  std::vector<int> source_frames;  ///< their indices in the input sequence, ascending
};

/// A new sequence at `out` (checked by `policy` before anything is read) holding the frames of the
/// depth sequence `sequence` that `labels` names (frame_index_from_name of each image's file name),
/// in frame order and numbered from 0, each with its depth, colour, time and pose and the instance
/// label image of its shapes whose label is in `classes` (empty: every shape), ids counting up from 1
/// over the whole sequence. Frames the labels do not name are left out: a frame nobody labelled is
/// not a frame without heads. groundtruth.json records the source and the source frames, and no
/// instance: a 2D label carries no field position or size. Throws Error(file, ...) for an image
/// name without a frame number, a frame past the end or named twice, a size other than the
/// depth's, or labels that name no frame.
LabelledSequenceSummary write_labelled_sequence(const std::filesystem::path& sequence, const LabelSet& labels,
                                                const std::vector<std::string>& classes,
                                                const std::filesystem::path& out, const OutputPolicy& policy,
                                                const std::string& source);

}  // namespace cropsight::io
