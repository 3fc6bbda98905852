#include "cropsight/nn/onnx_detector.hpp"

#include <filesystem>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

#include "cropsight/core/error.hpp"
#include "cropsight/nn/center_net.hpp"
#include "nn/onnx_check.hpp"
#include "nn/onnx_decode.hpp"

namespace cropsight::nn {

static_assert(sizeof(Rgb8) == 3, "ColorImage rows are wrapped as CV_8UC3");

void OnnxDetectorConfig::validate(const std::string& where) const {
  check_config(*this, where);
  if (mean.size() != 1 && mean.size() != 3)
    throw Error(where, "'mean' needs 1 or 3 values, got " + std::to_string(mean.size()));
  if (names().empty()) throw Error(where, "'class_names' names no class");
}

std::vector<std::string> OnnxDetectorConfig::names() const { return split_class_names(class_names); }

namespace {
// OpenCV's messages span lines ("> Node [Add]... parse error: ..."); a cropsight::Error is one.
std::string one_line(const cv::Exception& e) {
  std::string out;
  for (char c : e.err.empty() ? std::string(e.what()) : e.err) {
    if (c == '\n' || c == '\r' || c == '>') c = ' ';
    if (c == ' ' && (out.empty() || out.back() == ' ')) continue;
    out += c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string shape_text(const cv::Mat& m) {
  std::string s = "[";
  for (int d = 0; d < m.dims; ++d) s += (d ? ", " : "") + std::to_string(m.size[d]);
  return s + "]";
}

// While loading and checking, OpenCV logs each failure itself (several ERROR lines on stderr);
// the Error thrown is the one line the user sees.
struct QuietOpenCv {
  cv::utils::logging::LogLevel before = cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  ~QuietOpenCv() { cv::utils::logging::setLogLevel(before); }
};
}  // namespace

struct OnnxDetector::Impl {
  cv::dnn::Net net;
  std::string output;  // blob name forwarded
  std::vector<std::string> names;
  cv::Mat canvas, resized, blob;

  // The output's last two dimensions as (rows, cols) for decode_rows, after checking that its
  // shape is the layout's; throws Error(model) otherwise.
  static std::pair<int, int> table_of(const cv::Mat& out, const OnnxDetectorConfig& cfg, std::size_t classes) {
    const auto fail = [&](const std::string& expected) {
      throw Error(cfg.model, "output " + shape_text(out) + " is not the " + config_name(cfg.layout) + " layout " +
                                 expected + " (detector.onnx.layout)");
    };
    const int d = out.dims;
    switch (cfg.layout) {
      case OnnxLayout::yolov5:
        if (d != 3 || out.size[0] != 1 || out.size[2] < 6) fail("[1, N, 5 + C]");
        if (std::size_t(out.size[2] - 5) != classes) break;
        return {out.size[1], out.size[2]};
      case OnnxLayout::yolov8:
        if (d != 3 || out.size[0] != 1 || out.size[1] < 5) fail("[1, 4 + C, N]");
        if (std::size_t(out.size[1] - 4) != classes) break;
        return {out.size[1], out.size[2]};
      case OnnxLayout::ssd:
        if (d != 4 || out.size[0] != 1 || out.size[1] != 1 || out.size[3] != 7) fail("[1, 1, N, 7]");
        return {out.size[2], 7};
    }
    const int c = cfg.layout == OnnxLayout::yolov5 ? out.size[2] - 5 : out.size[1] - 4;
    throw Error(cfg.model, "output " + shape_text(out) + " has " + std::to_string(c) + " classes but class_names has " +
                               std::to_string(classes) + " (detector.onnx.class_names)");
  }

  cv::Mat forward(const cv::Mat& input_blob) {
    net.setInput(input_blob);
    return net.forward(output);
  }
};

OnnxDetector::OnnxDetector(OnnxDetectorConfig cfg) : cfg_(std::move(cfg)), impl_(std::make_unique<Impl>()) {
  cfg_.validate();
  impl_->names = cfg_.names();
  const std::string& path = cfg_.model;
  if (path.empty()) throw Error("detector.onnx.model", "no ONNX model given");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path, "no such ONNX file");
  check_onnx_tensors(path);  // OpenCV's importer trusts the tensors' shapes (nn/onnx_check.hpp)
  QuietOpenCv quiet;
  try {
    impl_->net = cv::dnn::readNetFromONNX(path);
  } catch (const cv::Exception& e) {
    throw Error(path, "not an ONNX model OpenCV " CV_VERSION " can load: " + one_line(e));
  }
  if (impl_->net.empty()) throw Error(path, "the ONNX file holds no network");
  try {
    impl_->output = cfg_.output.empty() ? impl_->net.getUnconnectedOutLayersNames().at(0) : cfg_.output;
  } catch (const std::exception&) {
    throw Error(path, "the network has no output");
  }
  // One blank input of the configured size: a network exported for another size fails here.
  const cv::Mat blank(std::vector<int>{1, 3, cfg_.input_height, cfg_.input_width}, CV_32F, cv::Scalar(0));
  cv::Mat out;
  try {
    out = impl_->forward(blank);
  } catch (const cv::Exception& e) {
    throw Error(path, "the network does not run on a 3 x " + std::to_string(cfg_.input_height) + " x " +
                          std::to_string(cfg_.input_width) +
                          " input (exported for another size than detector.onnx.input_width/input_height, or a "
                          "layer OpenCV " CV_VERSION " cannot run): " +
                          one_line(e));
  }
  Impl::table_of(out, cfg_, impl_->names.size());
}

OnnxDetector::~OnnxDetector() = default;

std::vector<std::string> OnnxDetector::class_names() const { return impl_->names; }

std::vector<Detection2D> OnnxDetector::detect(const DetectorInput& in) {
  if (in.image == nullptr || in.image->empty()) throw Error(cfg_.model, "detect() needs a colour image");
  const ColorImage& img = *in.image;
  const Letterbox lb = Letterbox::fit(img.width, img.height, cfg_.input_width, cfg_.input_height, cfg_.resize);
  Impl& m = *impl_;

  // Letterbox: resize into the centre of a pad-coloured canvas of the input size.
  const cv::Mat rgb(img.height, img.width, CV_8UC3, const_cast<Rgb8*>(img.data.data()));
  m.canvas.create(cfg_.input_height, cfg_.input_width, CV_8UC3);
  m.canvas.setTo(cv::Scalar::all(cfg_.pad_value));
  cv::Mat roi = m.canvas(cv::Rect(lb.pad_x, lb.pad_y, lb.resized_w, lb.resized_h));
  if (lb.resized_w == img.width && lb.resized_h == img.height)
    rgb.copyTo(roi);
  else
    cv::resize(rgb, roi, roi.size(), 0, 0, cv::INTER_LINEAR);
  const cv::Scalar mean =
      cfg_.mean.size() == 3 ? cv::Scalar(cfg_.mean[0], cfg_.mean[1], cfg_.mean[2]) : cv::Scalar::all(cfg_.mean[0]);
  // The canvas is RGB; swapRB gives the network BGR.
  cv::dnn::blobFromImage(m.canvas, m.blob, cfg_.scale, cv::Size(), mean, cfg_.channel_order == ChannelOrder::bgr, false,
                         CV_32F);
  cv::Mat out;
  try {
    out = m.forward(m.blob);
  } catch (const cv::Exception& e) {
    throw Error(cfg_.model, "forward pass failed: " + one_line(e));
  }
  const auto [rows, cols] = Impl::table_of(out, cfg_, m.names.size());
  if (!out.isContinuous()) out = out.clone();
  const auto candidates =
      decode_rows(cfg_.layout, out.ptr<float>(), rows, cols, lb, float(cfg_.confidence_threshold), cfg_.label_offset);
  auto boxes = nms_per_class(candidates, float(cfg_.iou_threshold), cfg_.max_detections);
  for (const Detection2D& d : boxes)
    if (d.class_id >= int(m.names.size()))
      throw Error(cfg_.model, "label " + std::to_string(d.class_id + cfg_.label_offset) + " has no class name (" +
                                  std::to_string(m.names.size()) +
                                  " in detector.onnx.class_names; detector.onnx.label_offset " +
                                  std::to_string(cfg_.label_offset) + ")");
  return boxes;
}

std::unique_ptr<Detector2D> make_onnx_detector(const OnnxDetectorConfig& cfg) {
  return std::make_unique<OnnxDetector>(cfg);
}

}  // namespace cropsight::nn
