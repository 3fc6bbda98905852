// nn::CenterNet: the facade over the plugin's DetectorBackend. Letterboxing, target encoding,
// batching, the training schedule (cosine learning rate, checkpoints) and validation AP50 run
// here, without libtorch; the network runs in the plugin.
#include "cropsight/nn/center_net.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <random>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/eval/voc_ap.hpp"
#include "nn/center_codec.hpp"
#include "nn/center_onnx_writer.hpp"
#include "nn/segmenter_backend.hpp"

namespace cropsight::nn {

struct CenterNet::Impl {
  std::unique_ptr<detail::DetectorBackend> backend;
};

namespace {

// A per-class mask letterboxed like the image, then averaged down to the output cells (a cell is
// inside when at least half of it is).
GrayImage mask_to_cells(const GrayImage& m, const Letterbox& lb, int ow, int oh) {
  cv::Mat canvas(lb.input_h, lb.input_w, CV_8UC1, cv::Scalar(0));
  const cv::Mat src(m.height, m.width, CV_8UC1, const_cast<std::uint8_t*>(m.data.data()));
  cv::Mat bin = src > 0;
  cv::Mat roi = canvas(cv::Rect(lb.pad_x, lb.pad_y, lb.resized_w, lb.resized_h));
  cv::resize(bin, roi, roi.size(), 0, 0, cv::INTER_NEAREST);
  cv::Mat cells;
  cv::resize(canvas, cells, cv::Size(ow, oh), 0, 0, cv::INTER_AREA);
  GrayImage out(ow, oh);
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) out.at(x, y) = cells.at<std::uint8_t>(y, x) >= 128 ? 1 : 0;
  return out;
}

// Appends one sample (letterboxed, encoded) to the batch.
void add_to_batch(detail::DetectorBatch& b, const DetectionSample& s, const CenterNetConfig& cfg) {
  if (s.image.empty()) throw Error(s.name.empty() ? "detector" : s.name, "empty training image");
  Letterbox lb;
  const auto blob = center_blob(s.image, cfg.input_width, cfg.input_height, &lb);
  const int ow = cfg.input_width / kCenterStride, oh = cfg.input_height / kCenterStride;
  std::vector<Detection2D> boxes;
  for (auto d : s.boxes) {
    d.x1 = d.x1 * lb.scale_x + float(lb.pad_x), d.x2 = d.x2 * lb.scale_x + float(lb.pad_x);
    d.y1 = d.y1 * lb.scale_y + float(lb.pad_y), d.y2 = d.y2 * lb.scale_y + float(lb.pad_y);
    boxes.push_back(d);
  }
  std::vector<GrayImage> masks;
  for (const auto& m : s.masks) {
    if (m.width != s.image.width || m.height != s.image.height)
      throw Error(s.name.empty() ? "detector" : s.name, "mask size differs from the image size");
    masks.push_back(mask_to_cells(m, lb, ow, oh));
  }
  const CenterTargets t = encode_targets(boxes, masks, cfg.num_classes(), ow, oh, cfg.max_objects);
  auto append = [](auto& dst, const auto& src) { dst.insert(dst.end(), src.begin(), src.end()); };
  append(b.images, blob), append(b.heatmap, t.heatmap), append(b.index, t.index);
  append(b.size, t.size), append(b.offset, t.offset), append(b.reg_mask, t.reg_mask);
  b.mask_present.push_back(t.mask.empty() ? 0.f : 1.f);
  if (t.mask.empty())
    b.mask.insert(b.mask.end(), t.heatmap.size(), 0.f);
  else
    append(b.mask, t.mask);
  ++b.n;
}

// Mean over the classes with truths of VOC all-point AP at IoU 0.5 (eval/voc_ap.hpp).
double mean_ap50(const CenterNet& net, const std::vector<DetectionSample>& val) {
  const int classes = net.config().num_classes();
  std::vector<std::vector<eval::VocImage>> per_class(std::size_t(classes), std::vector<eval::VocImage>(val.size()));
  auto voc = [](const Detection2D& d) { return eval::VocBox{d.x1, d.y1, d.x2, d.y2, d.score}; };
  for (std::size_t i = 0; i < val.size(); ++i) {
    for (const auto& t : val[i].boxes)
      if (t.class_id >= 0 && t.class_id < classes) per_class[std::size_t(t.class_id)][i].truth.push_back(voc(t));
    for (const auto& d : net.detect(val[i].image)) per_class[std::size_t(d.class_id)][i].detections.push_back(voc(d));
  }
  double sum = 0;
  int n = 0;
  for (const auto& images : per_class) {
    const double ap = eval::voc_ap(images, 0.5);
    if (std::isfinite(ap)) sum += ap, ++n;
  }
  return n ? sum / n : 0.0;
}

}  // namespace

CenterNet::CenterNet() = default;
CenterNet::CenterNet(const CenterNetConfig& cfg) : impl_(std::make_unique<Impl>()) {
  cfg.validate("detector");  // before the plugin: a bad config is named even without it
  impl_->backend = detail::backend_api().create_detector(cfg);
}
CenterNet::~CenterNet() = default;
CenterNet::CenterNet(CenterNet&&) noexcept = default;
CenterNet& CenterNet::operator=(CenterNet&&) noexcept = default;

const CenterNetConfig& CenterNet::config() const { return impl_->backend->config(); }
std::size_t CenterNet::parameter_count() const { return impl_->backend->parameter_count(); }
std::vector<std::string> CenterNet::class_names() const { return config().names(); }

DetectorLosses CenterNet::train_step(const std::vector<const DetectionSample*>& batch) {
  detail::DetectorBatch b;
  for (const auto* s : batch) add_to_batch(b, *s, config());
  return impl_->backend->train_step(b);
}

std::vector<DetectorEpochLog> CenterNet::train(
    const std::vector<DetectionSample>& train, const std::vector<DetectionSample>& val,
    const std::function<DetectionSample(const DetectionSample&, std::uint64_t)>& augment,
    const std::function<void(const DetectorEpochLog&)>& on_epoch, const std::filesystem::path& checkpoint) {
  if (train.empty()) throw Error("train detector", "no training images");
  const CenterNetConfig cfg = config();
  int start = 0;
  if (!checkpoint.empty() && std::filesystem::exists(checkpoint)) start = impl_->backend->read_checkpoint(checkpoint);
  std::vector<DetectorEpochLog> logs;
  std::vector<std::size_t> order(train.size());
  for (int e = start; e < cfg.epochs; ++e) {
    Stopwatch timer;
    // Cosine decay from lr to lr / 20 over the epochs.
    const double lo = cfg.lr / 20;
    impl_->backend->set_lr(lo + 0.5 * (cfg.lr - lo) * (1 + std::cos(M_PI * double(e) / double(cfg.epochs))));
    // Each epoch draws from its own seed, so a resumed run repeats the epochs it skipped exactly.
    std::mt19937_64 rng(cfg.seed * 1000003ULL + std::uint64_t(e));
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::shuffle(order.begin(), order.end(), rng);
    DetectorEpochLog log;
    log.epoch = e + 1;
    int steps = 0;
    for (std::size_t i = 0; i < order.size(); i += std::size_t(cfg.batch_size)) {
      std::vector<DetectionSample> drawn;
      for (std::size_t j = i; j < std::min(order.size(), i + std::size_t(cfg.batch_size)); ++j)
        drawn.push_back(augment ? augment(train[order[j]], rng()) : train[order[j]]);
      std::vector<const DetectionSample*> ptrs;
      for (const auto& d : drawn) ptrs.push_back(&d);
      const DetectorLosses l = train_step(ptrs);
      log.loss += l.total, log.heatmap_loss += l.heatmap, log.size_loss += l.size;
      log.offset_loss += l.offset, log.mask_loss += l.mask;
      ++steps;
    }
    for (double* v : {&log.loss, &log.heatmap_loss, &log.size_loss, &log.offset_loss, &log.mask_loss}) *v /= steps;
    if (!val.empty()) log.val_ap50 = mean_ap50(*this, val);
    if (!checkpoint.empty()) impl_->backend->write_checkpoint(checkpoint, e + 1);
    log.seconds = timer.seconds();
    logs.push_back(log);
    if (on_epoch) on_epoch(log);
  }
  return logs;
}

namespace {
// The heads of one blob letterboxed to w x h; with `flip`, the blob and its mirror in one batch.
CenterNetHeads forward_one(const detail::DetectorBackend& backend, std::vector<float> blob, int w, int h, bool flip) {
  if (!flip) return backend.forward(blob, 1, w, h).front();
  const auto mirrored = mirrored_blob(blob, w, h);
  blob.insert(blob.end(), mirrored.begin(), mirrored.end());
  auto both = backend.forward(blob, 2, w, h);
  merge_mirrored_heads(both[0], both[1]);
  return std::move(both[0]);
}
}  // namespace

CenterNetHeads CenterNet::heads(const ColorImage& image) const {
  if (image.empty()) throw Error("detector", "detect() needs a colour image");
  const CenterNetConfig& cfg = config();
  CenterNetHeads out = forward_one(*impl_->backend, center_blob(image, cfg.input_width, cfg.input_height, nullptr),
                                   cfg.input_width, cfg.input_height, cfg.flip_test);
  for (const auto& [w, h] : cfg.mask_input_sizes())
    out.extra_masks.push_back(
        mask_pass(forward_one(*impl_->backend, center_blob(image, w, h, nullptr), w, h, cfg.mask_passes_flip()), w, h));
  return out;
}

std::vector<Detection2D> CenterNet::detect(const ColorImage& image) const {
  if (image.empty()) throw Error("detector", "detect() needs a colour image");
  const CenterNetConfig& cfg = config();
  Letterbox lb;
  const auto h = forward_one(*impl_->backend, center_blob(image, cfg.input_width, cfg.input_height, &lb),
                             cfg.input_width, cfg.input_height, cfg.flip_test);
  return decode_heads(h, lb, float(cfg.score_threshold), cfg.top_k);
}

std::vector<Detection2D> CenterNet::detect(const DetectorInput& in) {
  if (in.image == nullptr) throw Error("detector", "detect() needs a colour image");
  return detect(*in.image);
}

namespace {
// The one way an inference setting changes: the config with `edit` applied, validated (errors name
// `what`), handed to the backend; the weights stay.
template <class Edit>
void change_inference(detail::DetectorBackend& backend, const std::string& what, Edit&& edit) {
  CenterNetConfig c = backend.config();
  edit(c);
  c.validate("detector: " + what);
  backend.set_inference(c);
}
}  // namespace

void CenterNet::set_mask_thresholds(const std::vector<float>& per_class) {
  std::ostringstream list;
  list << std::setprecision(6);
  for (std::size_t c = 0; c < per_class.size(); ++c) list << (c ? "," : "") << per_class[c];
  change_inference(*impl_->backend, "mask thresholds", [&](CenterNetConfig& c) { c.mask_thresholds = list.str(); });
}

void CenterNet::set_input_size(int width, int height) {
  change_inference(*impl_->backend, "input size", [&](CenterNetConfig& c) {
    c.input_width = width;
    c.input_height = height;
  });
}

void CenterNet::set_flip_test(bool on) {
  change_inference(*impl_->backend, "flip test", [&](CenterNetConfig& c) { c.flip_test = on; });
}

void CenterNet::set_mask_inputs(const std::string& list, bool flip_test) {
  change_inference(*impl_->backend, "mask inputs", [&](CenterNetConfig& c) {
    c.mask_inputs = list;
    c.mask_inputs_flip_test = flip_test;
  });
}

void CenterNet::set_mask_upsampling(const std::string& mode) {
  change_inference(*impl_->backend, "mask upsampling", [&](CenterNetConfig& c) { c.mask_upsampling = mode; });
}

void CenterNet::save(const std::filesystem::path& path) const { impl_->backend->save(path); }

void CenterNet::export_onnx(const std::filesystem::path& path) const {
  write_center_onnx(config(), impl_->backend->folded_convs(), path);
}

CenterNet CenterNet::load(const std::filesystem::path& path, int threads) {
  CenterNet n;
  n.impl_ = std::make_unique<Impl>();
  n.impl_->backend = detail::backend_api().load_detector(path, threads);
  return n;
}

}  // namespace cropsight::nn
