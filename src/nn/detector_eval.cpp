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

namespace {

// The mask head's cells around each image column and row, through the letterbox: the scores of
// cells x0 and x1 mixed with weight wx on x1 (rows the same). Bilinear: the two cell centres
// around the pixel centre; nearest: the cell under it twice, weight 0.
struct CellMap {
  std::vector<int> x0, x1, y0, y1;
  std::vector<float> wx, wy;
};

void axis_cells(int pixels, float scale, int pad, float cell, int cells, bool bilinear, std::vector<int>& c0,
                std::vector<int>& c1, std::vector<float>& w) {
  c0.resize(std::size_t(pixels));
  c1.resize(std::size_t(pixels));
  w.assign(std::size_t(pixels), 0.0f);
  for (int i = 0; i < pixels; ++i) {
    const float at = ((float(i) + 0.5f) * scale + float(pad)) / cell;  // in cells; centres at k + 0.5
    if (!bilinear) {
      c0[std::size_t(i)] = c1[std::size_t(i)] = std::clamp(int(std::floor(at)), 0, cells - 1);
      continue;
    }
    const float f = at - 0.5f;
    const int k = int(std::floor(f));
    if (k < 0 || k >= cells - 1) {  // beyond the first or last centre: that cell alone
      c0[std::size_t(i)] = c1[std::size_t(i)] = k < 0 ? 0 : cells - 1;
      continue;
    }
    c0[std::size_t(i)] = k;
    c1[std::size_t(i)] = k + 1;
    w[std::size_t(i)] = f - float(k);
  }
}

// The cell map of a mask head of out_w x out_h cells computed from an input_w x input_h letterbox.
CellMap cell_map(int out_w, int out_h, int input_w, int input_h, bool bilinear, int image_w, int image_h) {
  const Letterbox lb = Letterbox::fit(image_w, image_h, input_w, input_h, OnnxResize::letterbox);
  const float sx = float(input_w) / float(out_w), sy = float(input_h) / float(out_h);
  CellMap m;
  axis_cells(image_w, lb.scale_x, lb.pad_x, sx, out_w, bilinear, m.x0, m.x1, m.wx);
  axis_cells(image_h, lb.scale_y, lb.pad_y, sy, out_h, bilinear, m.y0, m.y1, m.wy);
  return m;
}

// Calls f(u, score) for every pixel of image row v of class plane p (out_w cells a row): the rows
// are mixed once into `line` (one value per cell), then each pixel mixes two cells of it.
template <class F>
void for_each_score(const CellMap& m, const float* p, int out_w, int v, std::vector<float>& line, F&& f) {
  const float* r0 = p + std::size_t(m.y0[std::size_t(v)]) * std::size_t(out_w);
  const float* r1 = p + std::size_t(m.y1[std::size_t(v)]) * std::size_t(out_w);
  const float wy = m.wy[std::size_t(v)];
  line.resize(std::size_t(out_w));
  for (int x = 0; x < out_w; ++x) line[std::size_t(x)] = r0[x] + wy * (r1[x] - r0[x]);
  const int w = int(m.x0.size());
  for (int u = 0; u < w; ++u) {
    const float a = line[std::size_t(m.x0[std::size_t(u)])], b = line[std::size_t(m.x1[std::size_t(u)])];
    f(u, a + m.wx[std::size_t(u)] * (b - a));
  }
}

// The mask scores of one image at its pixels, class by class and row by row: the main mask head's
// and, with CenterNetConfig::mask_inputs, each extra pass's, each brought to the image through its
// own letterbox and averaged (multi-scale test).
class MaskScores {
 public:
  MaskScores(const CenterNetHeads& heads, const CenterNetConfig& cfg, int image_w, int image_h)
      : classes_(heads.classes), row_(std::size_t(std::max(image_w, 0))) {
    const bool bilinear = cfg.mask_upsampling != "nearest";
    add(heads.mask, heads.out_w, heads.out_h, cfg.input_width, cfg.input_height, bilinear, image_w, image_h);
    for (const auto& p : heads.extra_masks)
      add(p.mask, p.out_w, p.out_h, p.input_w, p.input_h, bilinear, image_w, image_h);
  }

  /// Scores of class c along image row v (image_w values, valid until the next call).
  const float* row(int c, int v) {
    const float inv = 1.0f / float(passes_.size());
    for (std::size_t k = 0; k < passes_.size(); ++k) {
      const Pass& p = passes_[k];
      const float* plane = p.mask + std::size_t(c) * std::size_t(p.out_w) * std::size_t(p.out_h);
      if (k == 0)
        for_each_score(p.cells, plane, p.out_w, v, line_, [&](int u, float s) { row_[std::size_t(u)] = s; });
      else
        for_each_score(p.cells, plane, p.out_w, v, line_, [&](int u, float s) { row_[std::size_t(u)] += s; });
    }
    if (passes_.size() > 1)
      for (auto& s : row_) s *= inv;
    return row_.data();
  }

 private:
  struct Pass {
    CellMap cells;
    const float* mask = nullptr;
    int out_w = 0, out_h = 0;
  };
  void add(const std::vector<float>& mask, int out_w, int out_h, int input_w, int input_h, bool bilinear, int image_w,
           int image_h) {
    if (out_w <= 0 || out_h <= 0 || mask.size() != std::size_t(classes_) * std::size_t(out_w) * std::size_t(out_h))
      throw Error("detector", "a mask head's size does not match its cells");
    passes_.push_back(
        {cell_map(out_w, out_h, input_w, input_h, bilinear, image_w, image_h), mask.data(), out_w, out_h});
  }
  int classes_;
  std::vector<Pass> passes_;
  std::vector<float> line_, row_;
};

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

std::vector<Detection2D> boxes_from_heads(const CenterNetHeads& heads, const CenterNetConfig& cfg, int image_w,
                                          int image_h) {
  const Letterbox lb = Letterbox::fit(image_w, image_h, cfg.input_width, cfg.input_height, OnnxResize::letterbox);
  return decode_heads(heads, lb, float(cfg.score_threshold), cfg.top_k);
}

std::vector<GrayImage> masks_from_heads(const CenterNetHeads& heads, const CenterNetConfig& cfg, int image_w,
                                        int image_h, float threshold) {
  MaskScores scores(heads, cfg, image_w, image_h);
  const std::vector<float> per_class = threshold < 0
                                           ? cfg.mask_threshold_values()
                                           : std::vector<float>(std::size_t(std::max(heads.classes, 0)), threshold);
  std::vector<GrayImage> out;
  for (int c = 0; c < heads.classes; ++c) {
    const float t = std::size_t(c) < per_class.size() ? per_class[std::size_t(c)] : 0.5f;
    GrayImage m(image_w, image_h, 0);
    for (int v = 0; v < image_h; ++v) {
      auto* row = m.row(v);
      const float* score = scores.row(c, v);
      for (int u = 0; u < image_w; ++u) row[u] = score[u] >= t ? 255 : 0;
    }
    out.push_back(std::move(m));
  }
  return out;
}

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
                                double* ms_per_image) {
  const AnyCenterNet net(detector, "eval detector");
  const CenterNetConfig& cfg = net.cfg;
  DetectorEvaluator ev(cfg.names());
  double seconds = 0;
  for (const auto& s : samples) {
    const Stopwatch clock;
    const CenterNetHeads h = net.heads(s.image);
    const auto boxes = boxes_from_heads(h, cfg, s.image.width, s.image.height);
    seconds += clock.seconds();
    ev.add(s, boxes, masks_from_heads(h, cfg, s.image.width, s.image.height, mask_threshold));
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
