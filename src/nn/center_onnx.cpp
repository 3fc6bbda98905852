// nn::CenterNetOnnx: the exported CenterNet through OpenCV DNN (include/cropsight/nn/center_onnx.hpp).
#include "cropsight/nn/center_onnx.hpp"

#include <opencv2/core/utils/logger.hpp>
#include <opencv2/dnn.hpp>

#include "cropsight/core/error.hpp"
#include "nn/center_codec.hpp"
#include "nn/center_onnx_writer.hpp"
#include "nn/onnx_check.hpp"

namespace cropsight::nn {

namespace {
const std::vector<std::string> kOutputs = {"heatmap", "size", "offset", "mask"};

std::string first_line(const cv::Exception& e) {
  const std::string s = e.what();
  const auto p = s.find("error: ");
  std::string t = p == std::string::npos ? s : s.substr(p + 7);
  return t.substr(0, t.find('\n'));
}
}  // namespace

struct CenterNetOnnx::Impl {
  std::string where;
  CenterNetConfig cfg;
  cv::dnn::Net net;
  // cfg.mask_input_sizes(), parsed once. The one network runs them all: OpenCV DNN reshapes it
  // when the input size changes. A network per size (read from the same file) measured the same
  // in bench_detector's OnnxMasks row (2026-12-05, 640x352 with the flip test + unflipped 768x448,
  // two runs each: 99.6-119 ms with a network per size against 97.4-108 ms with one; the VM's
  // noise is larger than any difference), so it is not kept.
  std::vector<std::pair<int, int>> extra_sizes;

  // One pass of a blob letterboxed to w x h (the graph is fully convolutional and its Resize nodes
  // take scales, so any multiple of 32 runs); mask_only computes the mask head alone.
  std::vector<cv::Mat> forward(const std::vector<float>& blob, int w, int h, bool mask_only) {
    const int dims[4] = {1, 3, h, w};
    net.setInput(cv::Mat(4, dims, CV_32F, const_cast<float*>(blob.data())));
    std::vector<cv::Mat> outs;
    try {
      if (mask_only)
        net.forward(outs, kOutputs.back());  // the other heads' layers are skipped
      else
        net.forward(outs, kOutputs);
    } catch (const cv::Exception& e) {
      throw Error(where, "forward pass failed: " + first_line(e));
    }
    return outs;
  }

  // The heads of one pass; with mask_only (an extra mask pass) only the mask head, the others empty.
  CenterNetHeads heads(const std::vector<float>& blob, int w, int hgt, bool mask_only = false) {
    const auto outs = forward(blob, w, hgt, mask_only);
    CenterNetHeads h;
    h.classes = cfg.num_classes(), h.out_w = w / 4, h.out_h = hgt / 4;
    const std::size_t plane = std::size_t(h.out_w) * std::size_t(h.out_h);
    std::vector<float>* dst[4] = {&h.heatmap, &h.size, &h.offset, &h.mask};
    const std::size_t channels[4] = {std::size_t(h.classes), 2, 2, std::size_t(h.classes)};
    for (int i = mask_only ? 3 : 0; i < 4; ++i) {
      const cv::Mat& m = outs[std::size_t(mask_only ? 0 : i)];
      if (m.total() != channels[i] * plane || m.type() != CV_32F)
        throw Error(where, "output '" + kOutputs[std::size_t(i)] + "' has a foreign layout (expected [1, " +
                               std::to_string(channels[i]) + ", " + std::to_string(h.out_h) + ", " +
                               std::to_string(h.out_w) + "])");
      dst[i]->assign(m.ptr<float>(), m.ptr<float>() + m.total());
    }
    return h;
  }

  // The heads of a blob, averaged with those of its mirror when the model asks for the flip test
  // (the exported graph takes one image: two passes).
  CenterNetHeads flip_tested(const std::vector<float>& blob, int w, int hgt, bool flip, bool mask_only = false) {
    CenterNetHeads h = heads(blob, w, hgt, mask_only);
    if (flip) merge_mirrored_heads(h, heads(mirrored_blob(blob, w, hgt), w, hgt, mask_only));
    return h;
  }
};

CenterNetOnnx::CenterNetOnnx(const std::filesystem::path& path) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.where = path.string();
  if (std::error_code ec; !std::filesystem::is_regular_file(path, ec)) throw Error(m.where, "no such ONNX file");
  const OnnxModelInfo info = read_onnx_info(path);
  if (info.metadata.count("kind") == 0 || info.metadata.at("kind") != "cropsight-centernet")
    throw Error(m.where, "not a cropsight detector (no cropsight.kind metadata; a foreign ONNX layout?)");
  ConfigMap map(info.metadata.begin(), info.metadata.end());
  map.erase("kind");
  m.cfg.mask_upsampling = "nearest";  // what a model written before the key was calibrated for
  apply_config(m.cfg, map, m.where + ": metadata");
  m.cfg.validate(m.where + ": metadata");
  m.extra_sizes = m.cfg.mask_input_sizes(m.where);
  for (const auto& o : kOutputs)
    if (std::find(info.outputs.begin(), info.outputs.end(), o) == info.outputs.end())
      throw Error(m.where, "has no output '" + o + "' (a foreign ONNX layout)");
  check_onnx_tensors(path);  // OpenCV's importer trusts the tensors' shapes (nn/onnx_check.hpp)
  const auto level = cv::utils::logging::getLogLevel();
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  try {
    m.net = cv::dnn::readNetFromONNX(m.where);
  } catch (const cv::Exception& e) {
    cv::utils::logging::setLogLevel(level);
    throw Error(m.where, "not an ONNX model OpenCV " CV_VERSION " can load: " + first_line(e));
  }
  cv::utils::logging::setLogLevel(level);
  // One blank input: a file whose outputs do not fit fails here, not on the first image.
  m.heads(std::vector<float>(3 * std::size_t(m.cfg.input_width) * std::size_t(m.cfg.input_height), 0.5f),
          m.cfg.input_width, m.cfg.input_height);
}

CenterNetOnnx::~CenterNetOnnx() = default;
const CenterNetConfig& CenterNetOnnx::config() const { return impl_->cfg; }
std::vector<std::string> CenterNetOnnx::class_names() const { return impl_->cfg.names(); }

CenterNetHeads CenterNetOnnx::heads(const ColorImage& image) {
  if (image.empty()) throw Error(impl_->where, "detect() needs a colour image");
  const CenterNetConfig& cfg = impl_->cfg;
  CenterNetHeads out = impl_->flip_tested(center_blob(image, cfg.input_width, cfg.input_height, nullptr),
                                          cfg.input_width, cfg.input_height, cfg.flip_test);
  for (const auto& [w, h] : impl_->extra_sizes)
    out.extra_masks.push_back(
        mask_pass(impl_->flip_tested(center_blob(image, w, h, nullptr), w, h, cfg.mask_passes_flip(), true), w, h));
  return out;
}

std::vector<Detection2D> CenterNetOnnx::detect(const ColorImage& image) {
  if (image.empty()) throw Error(impl_->where, "detect() needs a colour image");
  Letterbox lb;
  const auto blob = center_blob(image, impl_->cfg.input_width, impl_->cfg.input_height, &lb);
  return decode_heads(impl_->flip_tested(blob, impl_->cfg.input_width, impl_->cfg.input_height, impl_->cfg.flip_test),
                      lb, float(impl_->cfg.score_threshold), impl_->cfg.top_k);
}

std::vector<Detection2D> CenterNetOnnx::detect(const DetectorInput& in) {
  if (in.image == nullptr) throw Error(impl_->where, "detect() needs a colour image");
  return detect(*in.image);
}

const CenterNetConfig& center_net_config(const Detector2D& detector, const std::string& where) {
  if (const auto* onnx = dynamic_cast<const CenterNetOnnx*>(&detector)) return onnx->config();
  if (const auto* net = dynamic_cast<const CenterNet*>(&detector)) return net->config();
  throw Error(where, "the model is not a cropsight CenterNet (.pt or .onnx)");
}

std::unique_ptr<Detector2D> load_center_detector(const std::filesystem::path& path, int threads) {
  if (path.extension() == ".onnx") return std::make_unique<CenterNetOnnx>(path);
  return std::make_unique<CenterNet>(CenterNet::load(path, threads));
}

}  // namespace cropsight::nn
