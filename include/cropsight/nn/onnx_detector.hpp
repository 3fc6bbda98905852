#pragma once
// A user's ONNX detector run by OpenCV DNN (part of cropsight_nn, not of the libtorch plugin):
// the `onnx` backend of the potato pipeline's Detector2D.
//
// Per image: the colour image is fitted to the network's input size (letterbox: scaled to fit,
// aspect kept, centred on a pad colour; or stretched), made into an NCHW float blob
// ((pixel - mean) * scale, in the network's channel order), run, and the output decoded by layout:
//
//   yolov5  [1, N, 5 + C]  cx, cy, w, h in input pixels, objectness, C class scores;
//                          score = objectness × best class score (YOLOv5 export, opset 12)
//   yolov8  [1, 4 + C, N]  cx, cy, w, h in input pixels, C class scores, no objectness;
//                          score = best class score (what YOLOv8 exports output)
//                          OpenCV 4.6 runs this layout and YOLOv8's head ops (DFL, Split,
//                          dist2bbox, Sigmoid, Concat), but not a stock ultralytics export:
//                          it refuses an Add of two constants of different shapes (anchor
//                          grid; parseBias) and a Mul of the [1, 4, N] boxes by the [1, N]
//                          stride constant; tests/nn/test_onnx_detector.cpp shows all three.
//   ssd     [1, 1, N, 7]   DetectionOutput rows: image_id, label, confidence, x1, y1, x2, y2
//                          normalised to the input (label - label_offset = class index)
//
// Boxes are mapped back to the image (the letterbox undone), clipped to it, kept when
// score >= confidence_threshold, and suppressed per class with cv::dnn::NMSBoxes. Boxes come
// out in image pixels, continuous coordinates (core/detection2d.hpp), highest score first.
//
// The constructor loads the model and runs it once on a blank input, so that a missing, corrupt
// or foreign file, an input size the network does not take, or an output that matches no layout
// fails there with one cropsight::Error line naming the file, never on the first frame.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/core/detection2d.hpp"

namespace cropsight::nn {

enum class OnnxLayout { yolov5, yolov8, ssd };
constexpr std::array<const char*, 3> config_names(OnnxLayout) { return {"yolov5", "yolov8", "ssd"}; }

/// How the image is fitted to the network input: `letterbox` keeps the aspect ratio and pads
/// (YOLO training); `stretch` resizes each axis on its own (SSD's fixed-shape resizer).
enum class OnnxResize { letterbox, stretch };
constexpr std::array<const char*, 2> config_names(OnnxResize) { return {"letterbox", "stretch"}; }

enum class ChannelOrder { rgb, bgr };
constexpr std::array<const char*, 2> config_names(ChannelOrder) { return {"rgb", "bgr"}; }

/// Defaults are YOLOv5's export and inference conventions (ultralytics/yolov5 export.py and
/// detect.py); the preset configs/potato-onnx.yaml sets the user's model.
struct OnnxDetectorConfig {
  std::string model;  ///< path of the .onnx file
  OnnxLayout layout = OnnxLayout::yolov5;
  std::string output;                         ///< output blob name; empty = the network's first output
  int input_width = 640, input_height = 640;  ///< pixels; the size the network was exported for
  OnnxResize resize = OnnxResize::letterbox;
  int pad_value = 114;  ///< 0..255, grey of the letterbox border (YOLOv5: 114)
  ChannelOrder channel_order = ChannelOrder::rgb;
  double scale = 1.0 / 255.0;                  ///< blob = (pixel - mean) * scale
  std::vector<double> mean = {0.0, 0.0, 0.0};  ///< per channel, in channel_order, pixel units
  double confidence_threshold = 0.25;          ///< score in [0, 1] (YOLOv5 detect.py: 0.25)
  double iou_threshold = 0.45;                 ///< NMS IoU (YOLOv5 detect.py: 0.45)
  int max_detections = 300;                    ///< boxes kept per image (YOLOv5: 300)
  int label_offset = 0;                        ///< ssd only: label of class 0 (1 when 0 is background)
  std::string class_names = "potato";          ///< comma-separated, indexed by class id

  template <class V>
  void visit(V& v) {
    v("model", model, "path of the ONNX file (a user's detector; none ships)");
    v("layout", layout, "yolov5 [1,N,5+C] | yolov8 [1,4+C,N] | ssd DetectionOutput [1,1,N,7]");
    v("output", output, "output blob name; empty = the network's first output");
    v("input_width", input_width, "pixels; network input width (YOLOv5: 640; paper's SSD300: 300)",
      Range::within(8, 8192));
    v("input_height", input_height, "pixels; network input height (YOLOv5: 640; paper's SSD300: 300)",
      Range::within(8, 8192));
    v("resize", resize, "letterbox (aspect kept, padded; YOLO) | stretch (SSD fixed-shape resizer)");
    v("pad_value", pad_value, "0..255; letterbox border grey (YOLOv5: 114)", Range::within(0, 255));
    v("channel_order", channel_order, "rgb | bgr; channel order the network expects (YOLOv5: rgb)");
    v("scale", scale, "1/pixel; blob = (pixel - mean) * scale (YOLOv5: 1/255)", Range::above(0));
    v("mean", mean, "pixel units, per channel in channel_order, subtracted before scale (YOLOv5: 0)");
    v("confidence_threshold", confidence_threshold, "score; boxes below are dropped (YOLOv5 detect.py: 0.25)",
      Range::within(0, 1));
    v("iou_threshold", iou_threshold, "IoU; per-class NMS threshold (YOLOv5 detect.py: 0.45)", Range::within(0, 1));
    v("max_detections", max_detections, "count; boxes kept per image (YOLOv5: 300)", Range::at_least(1));
    v("label_offset", label_offset, "ssd only: label of class 0 (1 when label 0 is the background)",
      Range::at_least(0));
    v("class_names", class_names, "comma-separated class names, indexed by class id");
  }
  /// The Ranges above, then: mean has 1 or 3 values, class_names is not empty. Throws Error(where).
  void validate(const std::string& where = "detector.onnx") const;
  /// class_names split at commas, spaces around each name trimmed.
  std::vector<std::string> names() const;
};

class OnnxDetector final : public Detector2D {
 public:
  /// Loads cfg.model and checks it on one blank input (see the header comment). Throws Error.
  explicit OnnxDetector(OnnxDetectorConfig cfg);
  ~OnnxDetector() override;
  OnnxDetector(const OnnxDetector&) = delete;
  OnnxDetector& operator=(const OnnxDetector&) = delete;

  std::vector<Detection2D> detect(const DetectorInput& in) override;
  std::vector<std::string> class_names() const override;
  const OnnxDetectorConfig& config() const { return cfg_; }

 private:
  struct Impl;
  OnnxDetectorConfig cfg_;
  std::unique_ptr<Impl> impl_;
};

/// The `onnx` backend for a pipeline's detector slot.
std::unique_ptr<Detector2D> make_onnx_detector(const OnnxDetectorConfig& cfg);

}  // namespace cropsight::nn
