#include "cropsight/nn/detector_eval.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "center_codec.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/eval/coco_box_ap.hpp"
#include "cropsight/eval/segmentation_metrics.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "onnx_decode.hpp"

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

std::vector<GrayImage> masks_from_heads(const CenterNetHeads& heads, const CenterNetConfig& cfg, int image_w,
                                        int image_h, float threshold) {
  const Letterbox lb = Letterbox::fit(image_w, image_h, cfg.input_width, cfg.input_height, OnnxResize::letterbox);
  const float sx = float(cfg.input_width) / float(heads.out_w), sy = float(cfg.input_height) / float(heads.out_h);
  std::vector<int> cell_x(static_cast<std::size_t>(image_w)), cell_y(static_cast<std::size_t>(image_h));
  for (int u = 0; u < image_w; ++u)
    cell_x[std::size_t(u)] =
        std::clamp(int(std::floor(((float(u) + 0.5f) * lb.scale_x + float(lb.pad_x)) / sx)), 0, heads.out_w - 1);
  for (int v = 0; v < image_h; ++v)
    cell_y[std::size_t(v)] =
        std::clamp(int(std::floor(((float(v) + 0.5f) * lb.scale_y + float(lb.pad_y)) / sy)), 0, heads.out_h - 1);
  std::vector<GrayImage> out;
  const std::size_t plane = std::size_t(heads.out_w) * std::size_t(heads.out_h);
  for (int c = 0; c < heads.classes; ++c) {
    GrayImage m(image_w, image_h, 0);
    const float* p = heads.mask.data() + std::size_t(c) * plane;
    for (int v = 0; v < image_h; ++v) {
      const float* prow = p + std::size_t(cell_y[std::size_t(v)]) * std::size_t(heads.out_w);
      auto* row = m.row(v);
      for (int u = 0; u < image_w; ++u) row[u] = prow[cell_x[std::size_t(u)]] >= threshold ? 255 : 0;
    }
    out.push_back(std::move(m));
  }
  return out;
}

DetectorScore evaluate_detector(Detector2D& detector, const std::vector<DetectionSample>& samples, float mask_threshold,
                                double* ms_per_image) {
  auto* onnx = dynamic_cast<CenterNetOnnx*>(&detector);
  auto* torch_net = dynamic_cast<CenterNet*>(&detector);
  if (onnx == nullptr && torch_net == nullptr)
    throw Error("eval detector", "the model is not a cropsight CenterNet (.pt or .onnx)");
  const CenterNetConfig& cfg = onnx != nullptr ? onnx->config() : torch_net->config();
  DetectorEvaluator ev(cfg.names());
  double seconds = 0;
  for (const auto& s : samples) {
    const Stopwatch clock;
    const CenterNetHeads h = onnx != nullptr ? onnx->heads(s.image) : torch_net->heads(s.image);
    const Letterbox lb =
        Letterbox::fit(s.image.width, s.image.height, cfg.input_width, cfg.input_height, OnnxResize::letterbox);
    const auto boxes = decode_heads(h, lb, float(cfg.score_threshold), cfg.top_k);
    seconds += clock.seconds();
    ev.add(s, boxes, masks_from_heads(h, cfg, s.image.width, s.image.height, mask_threshold));
  }
  if (ms_per_image != nullptr) *ms_per_image = samples.empty() ? 0.0 : 1000.0 * seconds / double(samples.size());
  return ev.score();
}

}  // namespace cropsight::nn
