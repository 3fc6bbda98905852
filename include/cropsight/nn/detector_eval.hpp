#pragma once
// Scoring the 2D detector (nn::CenterNet, .pt or .onnx) on a labelled image set
// (`cropsight eval detector`): per class COCO box AP50 and AP50:95 (eval/coco_box_ap.hpp: COCO's
// matching and 101-point interpolation) and the grape paper's Table 2 2D segmentation metrics of
// the mask head, per class over the whole image set.
//
// Masks: the mask head mapped back to every image pixel and thresholded at mask_threshold
// (masks_from_heads, center_decode.hpp; the boxes are boxes_from_heads). Per class c, pixels are
// counted over all images that carry truth masks (DetectionSample::masks, COCO polygons filled):
// TP = in the truth and predicted, FN = in the truth only, FP = predicted only. IoU = TP / (TP +
// FP + FN); pixel accuracy = TP / (TP + FN) (the class's pixels labelled right,
// eval::ConfusionMatrix::class_accuracy). A pixel may belong to two classes (the masks are per
// class, not exclusive). Images without truth masks count for the box APs only.
#include <cstdint>
#include <string>
#include <vector>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"
#include "cropsight/nn/center_net.hpp"

namespace cropsight::nn {

struct DetectorClassScore {
  std::string name;
  std::int64_t truths = 0, detections = 0;  ///< boxes
  double ap50 = 0, ap50_95 = 0;             ///< NaN without a truth box
  std::int64_t truth_pixels = 0, predicted_pixels = 0, true_pixels = 0;
  double pixel_accuracy = 0, iou = 0;  ///< NaN without truth masks (pixel_accuracy) or any pixel (iou)
};

struct DetectorScore {
  std::vector<DetectorClassScore> classes;  ///< in class id order
  int images = 0, masked_images = 0;        ///< all scored / those with truth masks
};

/// Accumulates images: truth (boxes, optional per-class masks) and predictions (boxes with
/// class ids and scores, per-class predicted masks image-sized, non-zero = inside; empty = none).
class DetectorEvaluator {
 public:
  explicit DetectorEvaluator(std::vector<std::string> classes);
  void add(const DetectionSample& truth, const std::vector<Detection2D>& detections,
           const std::vector<GrayImage>& predicted_masks);
  DetectorScore score() const;

 private:
  std::vector<std::string> classes_;
  struct Image {
    std::vector<std::vector<Detection2D>> truth, dets;  // per class
  };
  std::vector<Image> images_;
  std::vector<std::int64_t> tp_, fp_, fn_;
  int masked_ = 0;
};

/// Runs `detector` (a CenterNet or CenterNetOnnx, as load_center_detector returns) on every
/// sample and scores it; masks at `mask_threshold` for every class, or (negative, the default)
/// at the model's per-class thresholds. `ms_per_image` (may be null) gets the mean time of the
/// network and the decoding per image. With `masks_in_boxes_only` the masks are those of
/// masks_in_boxes (center_decode.hpp: each class's mask only inside its detected boxes) instead of
/// masks_from_heads over the whole image. Throws Error for another kind of detector.
DetectorScore evaluate_detector(Detector2D& detector, const std::vector<DetectionSample>& samples,
                                float mask_threshold = -1.0f, double* ms_per_image = nullptr,
                                bool masks_in_boxes_only = false);

/// Per-class mask thresholds from labelled images: for each class, the value of the grid 0.05,
/// 0.10, ..., 0.95 whose masks have the best pixel IoU over all added images (the same pixels
/// and IoU as above), ties to the value nearest 0.5; 0.5 for a class without truth pixels.
/// Calibrate on training images only: a threshold read off the scored images is tuning on them.
class MaskCalibration {
 public:
  explicit MaskCalibration(int classes);
  /// One image's heads against its truth masks (an image without masks adds nothing).
  void add(const CenterNetHeads& heads, const CenterNetConfig& cfg, const DetectionSample& sample);
  std::vector<float> thresholds() const;  ///< per class id

 private:
  // Per class and grid bin: truth / other pixels whose score reaches exactly that many grid values.
  std::vector<std::int64_t> truth_, other_, total_;
};

/// MaskCalibration over `samples` with `detector`'s heads (a CenterNet or CenterNetOnnx).
std::vector<float> calibrate_mask_thresholds(Detector2D& detector, const std::vector<DetectionSample>& samples);

/// calibrate_mask_thresholds over `samples`, set on `net` (CenterNet::set_mask_thresholds) and
/// returned; empty, and nothing set, when no sample has masks (boxes alone calibrate nothing).
std::vector<float> calibrate_center_net_masks(CenterNet& net, const std::vector<DetectionSample>& samples);

}  // namespace cropsight::nn
