#pragma once
// Labelled image sets for the 2D detector (nn::CenterNet): COCO instance annotations (boxes and
// polygon masks) and Pascal VOC folders (boxes), read into DetectionSamples.
//
// Classes: the detector's class ids are positions in `classes`. COCO categories and VOC object
// names are matched to them by name; objects of other names are skipped. For COCO an empty
// `classes` means every category by increasing id except those named "_background_".
//
// Boxes are image pixels, continuous corners (COCO bbox [x, y, w, h] → x1 = x, x2 = x + w; VOC
// corners as written). COCO polygons are filled into per-class masks (DetectionSample::masks);
// an image with at least one polygon gets masks, others none. Errors are one line naming the
// file and the key: Error(ANN.json, "annotations[3]: no 'bbox'"), Error(image, ...) for an image
// that is missing or does not decode.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cropsight/nn/center_net.hpp"

namespace cropsight::nn {

struct DetectionDataset {
  std::vector<std::string> classes;
  std::vector<DetectionSample> samples;  ///< in the file's image order (VOC: by file name)
};

/// images[].file_name is looked up under `images_dir` (as written, then its file name alone).
DetectionDataset read_coco_detection(const std::filesystem::path& annotations, const std::filesystem::path& images_dir,
                                     const std::vector<std::string>& classes = {});

/// The COCO ids of a COCO file's images by file name (the name alone, without folders), so that
/// results on those images carry the annotations' ids. Throws Error(file, "images[3]: ...").
std::map<std::string, long> coco_image_ids(const std::filesystem::path& annotations);

/// Every *.xml of `voc_dir` (sorted), its <filename> under `images_dir` (else <stem>.jpg/.png).
/// `classes` must not be empty.
DetectionDataset read_voc_detection(const std::filesystem::path& voc_dir, const std::filesystem::path& images_dir,
                                    const std::vector<std::string>& classes);

/// The held-out split that train detector, eval detector and tune-mask-thresholds share, so that
/// each scores or calibrates on the images the others held out: round(fraction * n) samples (at
/// least one when fraction > 0 and n >= 2) drawn with `seed` are `val`, the others `train`; each
/// part in the set's order. Throws Error("--val-split", ...) unless 0 <= fraction < 1.
struct DetectionSplit {
  std::vector<DetectionSample> train, val;
};
DetectionSplit split_detection_set(std::vector<DetectionSample> samples, double fraction, std::uint64_t seed);

}  // namespace cropsight::nn
