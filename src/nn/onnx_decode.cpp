#include "nn/onnx_decode.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/dnn.hpp>

namespace cropsight::nn {

Letterbox Letterbox::fit(int image_w, int image_h, int input_w, int input_h, OnnxResize mode) {
  Letterbox lb;
  lb.image_w = image_w, lb.image_h = image_h;
  lb.input_w = input_w, lb.input_h = input_h;
  if (mode == OnnxResize::stretch) {
    lb.resized_w = input_w, lb.resized_h = input_h;
  } else {
    const double r = std::min(double(input_w) / image_w, double(input_h) / image_h);
    lb.resized_w = std::clamp(int(std::lround(image_w * r)), 1, input_w);
    lb.resized_h = std::clamp(int(std::lround(image_h * r)), 1, input_h);
    lb.pad_x = (input_w - lb.resized_w) / 2;
    lb.pad_y = (input_h - lb.resized_h) / 2;
  }
  lb.scale_x = float(lb.resized_w) / float(image_w);
  lb.scale_y = float(lb.resized_h) / float(image_h);
  return lb;
}

Detection2D Letterbox::to_image(float x1, float y1, float x2, float y2) const {
  Detection2D d;
  const float w = float(image_w), h = float(image_h);
  d.x1 = std::clamp((x1 - float(pad_x)) / scale_x, 0.f, w);
  d.x2 = std::clamp((x2 - float(pad_x)) / scale_x, 0.f, w);
  d.y1 = std::clamp((y1 - float(pad_y)) / scale_y, 0.f, h);
  d.y2 = std::clamp((y2 - float(pad_y)) / scale_y, 0.f, h);
  return d;
}

namespace {
// A candidate from a centre-size box in input pixels; dropped (false) when clipping empties it.
bool push_centre_box(std::vector<Detection2D>& out, const Letterbox& lb, const float* box, int cls, float score) {
  const float hw = 0.5f * box[2], hh = 0.5f * box[3];
  Detection2D d = lb.to_image(box[0] - hw, box[1] - hh, box[0] + hw, box[1] + hh);
  if (d.area() <= 0) return false;
  d.class_id = cls, d.score = score;
  out.push_back(d);
  return true;
}
}  // namespace

std::vector<Detection2D> decode_rows(OnnxLayout layout, const float* data, int rows, int cols, const Letterbox& lb,
                                     float threshold, int label_offset) {
  std::vector<Detection2D> out;
  switch (layout) {
    case OnnxLayout::yolov5: {
      const int classes = cols - 5;
      for (int i = 0; i < rows; ++i) {
        const float* p = data + std::size_t(i) * std::size_t(cols);
        // Class scores are probabilities (the export applies the sigmoid), so a row whose
        // objectness is below the threshold cannot reach it: most rows stop here.
        if (!(p[4] >= threshold)) continue;
        const int c = int(std::max_element(p + 5, p + 5 + classes) - (p + 5));
        const float score = p[4] * p[5 + c];
        if (score >= threshold) push_centre_box(out, lb, p, c, score);
      }
      break;
    }
    case OnnxLayout::yolov8: {
      // Channel-major: row r holds channel r of all N = cols boxes.
      const int classes = rows - 4;
      for (int n = 0; n < cols; ++n) {
        int best = 0;
        float score = data[std::size_t(4) * std::size_t(cols) + std::size_t(n)];
        for (int c = 1; c < classes; ++c) {
          const float s = data[std::size_t(4 + c) * std::size_t(cols) + std::size_t(n)];
          if (s > score) score = s, best = c;
        }
        if (!(score >= threshold)) continue;
        const float box[4] = {data[n], data[std::size_t(cols) + std::size_t(n)],
                              data[std::size_t(2) * std::size_t(cols) + std::size_t(n)],
                              data[std::size_t(3) * std::size_t(cols) + std::size_t(n)]};
        push_centre_box(out, lb, box, best, score);
      }
      break;
    }
    case OnnxLayout::ssd: {
      const float in_w = float(lb.input_w), in_h = float(lb.input_h);
      for (int i = 0; i < rows; ++i) {
        const float* p = data + std::size_t(i) * 7;
        const int cls = int(std::lround(p[1])) - label_offset;
        if (!(p[2] >= threshold) || cls < 0) continue;  // below threshold, or the background class
        Detection2D d = lb.to_image(p[3] * in_w, p[4] * in_h, p[5] * in_w, p[6] * in_h);
        if (d.area() <= 0) continue;
        d.class_id = cls, d.score = p[2];
        out.push_back(d);
      }
      break;
    }
  }
  return out;
}

std::vector<Detection2D> nms_per_class(const std::vector<Detection2D>& candidates, float iou_threshold,
                                       int max_detections) {
  std::map<int, std::vector<int>> by_class;
  for (int i = 0; i < int(candidates.size()); ++i) by_class[candidates[i].class_id].push_back(i);
  std::vector<int> kept;
  std::vector<cv::Rect2d> boxes;
  std::vector<float> scores;
  std::vector<int> picked;
  for (const auto& [cls, members] : by_class) {
    boxes.clear(), scores.clear(), picked.clear();
    for (int i : members) {
      const Detection2D& d = candidates[i];
      boxes.emplace_back(d.x1, d.y1, d.width(), d.height());
      scores.push_back(d.score);
    }
    // Thresholding is the decoder's; NMSBoxes only suppresses. It asserts a threshold >= 0 and
    // keeps scores above it, so a box of score exactly 0 never survives (not a detection).
    cv::dnn::NMSBoxes(boxes, scores, 0.f, iou_threshold, picked);
    for (int j : picked) kept.push_back(members[j]);
  }
  std::sort(kept.begin(), kept.end(), [&](int a, int b) {
    return candidates[a].score != candidates[b].score ? candidates[a].score > candidates[b].score : a < b;
  });
  if (int(kept.size()) > max_detections) kept.resize(std::size_t(max_detections));
  std::vector<Detection2D> out;
  out.reserve(kept.size());
  for (int i : kept) out.push_back(candidates[i]);
  return out;
}

}  // namespace cropsight::nn
