#include "cropsight/nn/detector_eval.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/eval/coco_box_ap.hpp"
#include "cropsight/eval/segmentation_metrics.hpp"
#include "cropsight/nn/center_decode.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "mask_upsampling.hpp"

namespace cropsight::nn {

DetectorEvaluator::DetectorEvaluator(std::vector<std::string> classes)
    : classes_(std::move(classes)), tp_(classes_.size(), 0), fp_(classes_.size(), 0), fn_(classes_.size(), 0) {}

void DetectorEvaluator::add(const DetectionSample& truth, const std::vector<Detection2D>& detections,
                            const std::vector<GrayImage>& predicted_masks) {
  const std::size_t n = classes_.size();
  Image im;
  im.truth.resize(n);
  im.dets.resize(n);
  for (const auto& b : truth.boxes)
    if (b.class_id >= 0 && std::size_t(b.class_id) < n) im.truth[std::size_t(b.class_id)].push_back(b);
  for (const auto& d : detections)
    if (d.class_id >= 0 && std::size_t(d.class_id) < n) im.dets[std::size_t(d.class_id)].push_back(d);
  images_.push_back(std::move(im));
  if (truth.masks.empty()) return;
  ++masked_;
  for (std::size_t c = 0; c < n && c < truth.masks.size(); ++c) {
    const GrayImage& t = truth.masks[c];
    const GrayImage* p = c < predicted_masks.size() ? &predicted_masks[c] : nullptr;
    if (p != nullptr && (p->width != t.width || p->height != t.height))
      throw Error(truth.name, "predicted mask of class " + classes_[c] + " is not image-sized");
    for (std::size_t i = 0; i < t.data.size(); ++i) {
      const bool in_t = t.data[i] != 0, in_p = p != nullptr && p->data[i] != 0;
      tp_[c] += in_t && in_p;
      fn_[c] += in_t && !in_p;
      fp_[c] += !in_t && in_p;
    }
  }
}

DetectorScore DetectorEvaluator::score() const {
  DetectorScore s;
  s.images = int(images_.size());
  s.masked_images = masked_;
  for (std::size_t c = 0; c < classes_.size(); ++c) {
    std::vector<eval::CocoApImage> per;
    per.reserve(images_.size());
    for (const auto& im : images_) per.push_back({im.truth[c], im.dets[c]});
    const auto ap = eval::coco_box_ap_summary(per);
    DetectorClassScore k;
    k.name = classes_[c];
    k.truths = ap.truths;
    k.detections = ap.detections;
    k.ap50 = ap.ap50;
    k.ap50_95 = ap.ap50_95;
    // Binary confusion of class c against the rest (1 = class c).
    eval::ConfusionMatrix cm(2);
    cm.add(1, 1, tp_[c]);
    cm.add(1, 0, fn_[c]);
    cm.add(0, 1, fp_[c]);
    k.true_pixels = tp_[c];
    k.truth_pixels = cm.truth_count(1);
    k.predicted_pixels = cm.pred_count(1);
    k.pixel_accuracy = masked_ > 0 ? cm.class_accuracy(1) : std::numeric_limits<double>::quiet_NaN();
    k.iou = masked_ > 0 ? cm.class_iou(1) : std::numeric_limits<double>::quiet_NaN();
    s.classes.push_back(std::move(k));
  }
  return s;
}

namespace {

// The thresholds calibrate_mask_thresholds() chooses from.
constexpr int kGrid = 19;
float grid_value(int j) { return 0.05f * float(j + 1); }

// The heads of one image from either kind of CenterNet (eval mode), and its configuration.
struct AnyCenterNet {
  Detector2D& detector;
  const CenterNetConfig& cfg;
  AnyCenterNet(Detector2D& d, const std::string& where) : detector(d), cfg(center_net_config(d, where)) {}
  CenterNetHeads heads(const ColorImage& image) const {
    if (auto* onnx = dynamic_cast<CenterNetOnnx*>(&detector)) return onnx->heads(image);
    return static_cast<const CenterNet&>(detector).heads(image);
  }
};

}  // namespace

MaskCalibration::MaskCalibration(int classes)
    : truth_(std::size_t(classes) * kGrid, 0), other_(truth_), total_(std::size_t(classes), 0) {}

void MaskCalibration::add(const CenterNetHeads& heads, const CenterNetConfig& cfg, const DetectionSample& sample) {
  if (sample.masks.empty()) return;
  const int classes = int(total_.size());
  const int w = sample.image.width, h = sample.image.height;
  MaskScores scores(heads, cfg, w, h);
  for (int c = 0; c < classes && c < heads.classes && std::size_t(c) < sample.masks.size(); ++c) {
    const GrayImage& t = sample.masks[std::size_t(c)];
    if (t.width != w || t.height != h)
      throw Error(sample.name, "truth mask of class " + std::to_string(c) + " is not image-sized");
    std::int64_t* in_truth = truth_.data() + std::size_t(c) * kGrid;
    std::int64_t* outside = other_.data() + std::size_t(c) * kGrid;
    for (int v = 0; v < h; ++v) {
      const auto* trow = t.row(v);
      const float* row = scores.row(c, v);
      for (int u = 0; u < w; ++u) {
        const float score = row[u];
        // Bin k counts pixels predicted at grid thresholds 0..k-1: score >= grid_value(j) for j < k.
        int k = 0;
        while (k < kGrid && score >= grid_value(k)) ++k;
        if (trow[u] != 0) {
          ++total_[std::size_t(c)];
          if (k > 0) ++in_truth[k - 1];
        } else if (k > 0) {
          ++outside[k - 1];
        }
      }
    }
  }
}

std::vector<float> MaskCalibration::thresholds() const {
  std::vector<float> out;
  for (std::size_t c = 0; c < total_.size(); ++c) {
    float best_t = 0.5f;
    double best_iou = -1;
    // TP(j) and FP(j): pixels whose bin is > j, i.e. summed from the top bin down.
    std::int64_t tp = 0, fp = 0;
    std::vector<double> iou(kGrid, 0.0);
    for (int j = kGrid - 1; j >= 0; --j) {
      tp += truth_[c * kGrid + std::size_t(j)];
      fp += other_[c * kGrid + std::size_t(j)];
      const std::int64_t fn = total_[c] - tp;
      iou[std::size_t(j)] = tp + fp + fn > 0 ? double(tp) / double(tp + fp + fn) : 0.0;
    }
    if (total_[c] > 0)
      for (int j = 0; j < kGrid; ++j) {
        const double d = std::abs(grid_value(j) - 0.5f), best_d = std::abs(best_t - 0.5f);
        if (iou[std::size_t(j)] > best_iou || (iou[std::size_t(j)] == best_iou && d < best_d))
          best_iou = iou[std::size_t(j)], best_t = grid_value(j);
      }
    out.push_back(best_t);
  }
  return out;
}

std::vector<float> calibrate_mask_thresholds(Detector2D& detector, const std::vector<DetectionSample>& samples) {
  const AnyCenterNet net(detector, "calibrate mask thresholds");
  const CenterNetConfig& cfg = net.cfg;
  MaskCalibration cal(cfg.num_classes());
  for (const auto& s : samples)
    if (!s.masks.empty()) cal.add(net.heads(s.image), cfg, s);
  return cal.thresholds();
}

DetectorScore evaluate_detector(Detector2D& detector, const std::vector<DetectionSample>& samples, float mask_threshold,
                                double* ms_per_image, bool masks_in_boxes_only) {
  const AnyCenterNet net(detector, "eval detector");
  const CenterNetConfig& cfg = net.cfg;
  DetectorEvaluator ev(cfg.names());
  double seconds = 0;
  for (const auto& s : samples) {
    const Stopwatch clock;
    const CenterNetHeads h = net.heads(s.image);
    const auto boxes = boxes_from_heads(h, cfg, s.image.width, s.image.height);
    seconds += clock.seconds();
    const int w = s.image.width, hgt = s.image.height;
    ev.add(s, boxes,
           masks_in_boxes_only ? masks_in_boxes(h, cfg, boxes, w, hgt, mask_threshold)
                               : masks_from_heads(h, cfg, w, hgt, mask_threshold));
  }
  if (ms_per_image != nullptr) *ms_per_image = samples.empty() ? 0.0 : 1000.0 * seconds / double(samples.size());
  return ev.score();
}

std::vector<float> calibrate_center_net_masks(CenterNet& net, const std::vector<DetectionSample>& samples) {
  if (std::none_of(samples.begin(), samples.end(), [](const auto& s) { return !s.masks.empty(); })) return {};
  const std::vector<float> t = calibrate_mask_thresholds(net, samples);
  net.set_mask_thresholds(t);
  return t;
}

}  // namespace cropsight::nn
