#pragma once
// The OpenCV-free half of the ONNX detector: the letterbox geometry and the decoding of the
// three output layouts into image boxes (include/cropsight/nn/onnx_detector.hpp), and per-class
// NMS. Separate from onnx_detector.cpp so that tests and bench/bench_onnx_detector.cpp can run
// the decoder on tables without a network.
#include <vector>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/nn/onnx_detector.hpp"

namespace cropsight::nn {

/// Where the image lies in the network input: input = image * scale + pad, per axis; the image
/// covers [pad_x, pad_x + resized_w) x [pad_y, pad_y + resized_h) of the input.
struct Letterbox {
  int image_w = 0, image_h = 0;
  int input_w = 0, input_h = 0;  ///< network input size, pixels
  int resized_w = 0, resized_h = 0;
  int pad_x = 0, pad_y = 0;  ///< left and top border, pixels
  float scale_x = 1, scale_y = 1;

  /// letterbox: one scale r = min(W / w, H / h), resized size round(w r) x round(h r) centred
  /// (the odd pixel of the border goes right / bottom); the per-axis scales are the exact
  /// resized / original ratios, so mapping back inverts the resize that was done. stretch: the
  /// image fills the input.
  static Letterbox fit(int image_w, int image_h, int input_w, int input_h, OnnxResize mode);
  /// Input-pixel box → image box, clipped to [0, image_w] x [0, image_h].
  Detection2D to_image(float x1, float y1, float x2, float y2) const;
};

/// Candidates with score >= threshold, in image pixels, before NMS. `rows` and `cols` are the
/// output's last two dimensions (yolov5: N x (5 + C); yolov8: (4 + C) x N; ssd: N x 7).
std::vector<Detection2D> decode_rows(OnnxLayout layout, const float* data, int rows, int cols, const Letterbox& lb,
                                     float threshold, int label_offset = 0);

/// Per-class NMS (cv::dnn::NMSBoxes, IoU > iou_threshold suppresses), then all classes merged,
/// highest score first (ties: earlier candidate first), at most max_detections. Boxes of score
/// 0 are dropped (NMSBoxes keeps scores > 0 only).
std::vector<Detection2D> nms_per_class(const std::vector<Detection2D>& candidates, float iou_threshold,
                                       int max_detections);

}  // namespace cropsight::nn
