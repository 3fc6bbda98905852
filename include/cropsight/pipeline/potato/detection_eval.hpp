#pragma once
// `eval potato-detection` in the library: a folder of images with Pascal VOC annotations, scored
// with the paper's metric (eval/voc_ap.hpp) either from saved detection files in the paper's
// text format or by running a Detector2D on every image.
//
// Layout: annotations_dir/*.xml (sorted by name: the image order of the ranking, as pascalvoc.py
// sorts its files); each names its image by <filename>, looked up in images_dir (a relative path
// names a subfolder of it; then the file name alone; then <stem>.jpg / <stem>.png). Saved detections:
// detections_dir/<stem>.txt for every annotation. Only objects and detections labelled `class_name` count.
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/eval/voc_ap.hpp"
#include "cropsight/io/voc.hpp"

namespace cropsight::pipeline::potato {

struct AnnotatedImage {
  std::filesystem::path image;  ///< the image file (exists)
  std::string stem;             ///< the annotation's file stem, for <stem>.txt
  io::VocAnnotation truth;
};

/// Every annotation of `annotations_dir` with its image. Throws Error naming the folder when it
/// holds no .xml, or the annotation whose image is missing.
std::vector<AnnotatedImage> load_annotated_images(const std::filesystem::path& images_dir,
                                                  const std::filesystem::path& annotations_dir);

/// Boxes of the class, as the metric takes them (corners as written; score 1 for truth).
std::vector<eval::VocBox> truth_boxes(const io::VocAnnotation& a, const std::string& class_name = "potato");
std::vector<eval::VocBox> detection_boxes(const std::vector<io::DetectionLine>& lines,
                                          const std::string& class_name = "potato");
std::vector<eval::VocBox> detection_boxes(const std::vector<Detection2D>& dets);

struct DetectionEvalResult {
  eval::VocApSummary ap;
  double ms_per_image = 0;  ///< detector time only, after one untimed warm-up call (0 for saved files)
};

/// Scores detections_dir/<stem>.txt against the annotations (Error naming a missing or bad file).
DetectionEvalResult evaluate_saved_detections(const std::vector<AnnotatedImage>& set,
                                              const std::filesystem::path& detections_dir,
                                              const std::string& class_name = "potato");

/// Runs `detector` on every image (read as 8-bit colour) and scores its class-0 boxes.
DetectionEvalResult evaluate_detector(Detector2D& detector, const std::vector<AnnotatedImage>& set,
                                      const std::string& class_name = "potato");

}  // namespace cropsight::pipeline::potato
