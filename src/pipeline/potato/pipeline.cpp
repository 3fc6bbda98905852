// The potato pipeline's composition (see potato/pipeline.hpp): one call per step of the paper.
#include "cropsight/pipeline/potato/pipeline.hpp"

#include <algorithm>
#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/depth_colormap.hpp"
#include "cropsight/nn/center_onnx.hpp"

namespace cropsight::pipeline::potato {

void Config::validate(const std::string& where) const {
  check_config(*this, where);
  detector.classical.validate(where);
  if (detector.backend == DetectorBackend::onnx) detector.onnx.validate(where);
  position.validate(where);
  measure::validate(orientation, where);
  cropsight::detail::check_range(where, "colormap_far_m", colormap_far_m,
                                 Range::above(colormap_near_m, "colormap_near_m"));
}

std::unique_ptr<Detector2D> make_detector(const DetectorConfig& cfg, const std::string& where) {
  if (cfg.backend == DetectorBackend::onnx) {
    if (cfg.onnx.model.empty())
      throw Error(where, "'detector.onnx.model' must name an .onnx file for detector.backend onnx");
    return nn::make_onnx_detector(cfg.onnx);
  }
  if (cfg.backend == DetectorBackend::cnn || cfg.backend == DetectorBackend::fusion) {
    if (cfg.cnn_model.empty())
      throw Error(where, "'detector.cnn_model' must name a detector (.onnx or .pt) for detector.backend " +
                             config_name(cfg.backend));
    auto cnn = nn::load_center_detector(cfg.cnn_model);
    if (cfg.backend == DetectorBackend::cnn) return cnn;
    std::vector<std::unique_ptr<Detector2D>> both;
    both.push_back(std::make_unique<BlobDetector>(cfg.classical));
    both.push_back(std::move(cnn));
    if (both.back()->class_names() != both.front()->class_names())
      throw Error(cfg.cnn_model, "detector.backend fusion needs a CNN of the one class 'potato'");
    return std::make_unique<FusedDetector>(std::move(both), cfg.fusion);
  }
  return std::make_unique<BlobDetector>(cfg.classical);
}

Pipeline::Pipeline(Config cfg, const std::string& where) : Pipeline(cfg, nullptr, where) {}

Pipeline::Pipeline(Config cfg, std::unique_ptr<Detector2D> detector, const std::string& where)
    : cfg_(std::move(cfg)), tracker_(cfg_.tracking) {
  cfg_.validate(where);
  detector_ = detector ? std::move(detector) : make_detector(cfg_.detector, where);
}

Pipeline::~Pipeline() = default;

void Pipeline::reset() { tracker_.reset(); }

ImageResult Pipeline::detect_image(const ColorImage& image, const Image<float>& depth_m, bool orient_boxes) {
  ImageResult r;
  {
    const auto scope = r.timer.scope("detect");
    r.detections = detector_->detect(DetectorInput{&image, depth_m.empty() ? nullptr : &depth_m});
  }
  if (!orient_boxes) return r;
  const auto scope = r.timer.scope("orient");
  for (const Detection2D& box : r.detections) {
    const measure::OrientationResult o = orient(image, depth_m, box);
    r.angles.push_back(o.ok ? std::optional<double>(o.angle_rad) : std::nullopt);
  }
  return r;
}

std::vector<std::string> Pipeline::detector_class_names() const { return detector_->class_names(); }

std::vector<tracking::TargetCandidate> Pipeline::candidates(const FrameResult& r) const {
  std::vector<tracking::TargetCandidate> c(r.detections.size());
  for (std::size_t i = 0; i < c.size(); ++i) {
    c[i].box = r.detections[i];
    c[i].distance_m = r.positions[i].surface_depth_m;
    c[i].ripe = r.ripe[i];
    c[i].depth_ok = r.positions[i].depth_ok;
  }
  return c;
}

// Step 5 on the target's box: the colourised depth (as the paper, from the frame's metric depth)
// or the colour image, as the preset says. Only the region the orientation step reads (the box
// widened by its margin, plus a pixel) is colourised: the colour map is per pixel, so the result is
// that of the whole frame's map, at a fraction of its cost (it was half of a frame's time).
measure::OrientationResult Pipeline::orient(const ColorImage& color, const Image<float>& depth_m,
                                            const Detection2D& box) const {
  const bool use_depth = cfg_.orientation.input == measure::OrientationInput::depth && !depth_m.empty();
  measure::OrientationConfig oc = cfg_.orientation;
  if (!use_depth) {
    oc.input = measure::OrientationInput::rgb;
    return measure::estimate_orientation(color, box, oc);
  }
  if (!std::isfinite(box.x1) || !std::isfinite(box.y1) || !std::isfinite(box.x2) || !std::isfinite(box.y2))
    return measure::estimate_orientation(color, box, oc);  // its one-line error for a bad box
  // One pixel more than the step reads, so that its own widening of the shifted box, rounded in
  // floating point, stays inside the crop.
  const auto [x0, y0, x1, y1] = measure::orientation_region(box, oc, depth_m.width, depth_m.height, 1);
  if (x1 - x0 < 3 || y1 - y0 < 3) return measure::estimate_orientation(color, box, oc);
  Image<float> crop(x1 - x0, y1 - y0);
  for (int v = y0; v < y1; ++v) std::copy(depth_m.row(v) + x0, depth_m.row(v) + x1, crop.row(v - y0));
  const ColorImage image = io::colorize_depth(crop, float(cfg_.colormap_near_m), float(cfg_.colormap_far_m));
  Detection2D shifted = box;
  shifted.x1 -= float(x0), shifted.x2 -= float(x0), shifted.y1 -= float(y0), shifted.y2 -= float(y0);
  measure::OrientationResult r = measure::estimate_orientation(image, shifted, oc);
  r.roi_x += x0;
  r.roi_y += y0;
  return r;
}

void Pipeline::orient_target(const RgbdFrame& frame, const Image<float>& depth_m, FrameResult& r) {
  HarvestTarget& t = r.target;
  const measure::OrientationResult o = orient(frame.color, depth_m, t.box);
  t.angle_ok = o.ok;
  t.angle = o.ok ? float(o.angle_rad) : 0.f;
}

FrameResult Pipeline::process(const RgbdFrame& frame) {
  if (frame.color.empty()) throw Error("frame " + std::to_string(frame.index), "the potato pipeline needs colour");
  FrameResult r;
  Stopwatch watch;
  const auto lap = [&watch] {
    const double ms = watch.ms();
    watch.restart();
    return ms;
  };
  const Image<float> depth_m =
      frame.depth.empty() ? Image<float>{} : measure::depth_in_metres(frame.depth, frame.camera.depth_scale);
  // 1. detect
  r.detections = detector_->detect(DetectorInput{&frame.color, depth_m.empty() ? nullptr : &depth_m});
  r.timer.add("detect", lap());
  // Without depth a box has no position (depth_ok false).
  const auto locate = [&](const Detection2D& box) {
    return depth_m.empty() ? measure::Position3D{} : measure::locate(box, depth_m, frame.camera, cfg_.position);
  };
  // 2. locate, 3. ripeness
  for (const Detection2D& d : r.detections) {
    r.positions.push_back(locate(d));
    r.ripe.push_back(measure::is_ripe(r.positions.back(), cfg_.ripeness));
  }
  r.timer.add("locate", lap());
  // 4. select / track
  const tracking::TargetUpdate u = tracker_.update(&frame.color, candidates(r));
  r.timer.add("track", lap());
  HarvestTarget& t = r.target;
  t.frame = frame.index;
  t.timestamp = frame.timestamp;
  t.state = u.state;
  t.target_id = u.target_id;
  if (u.box) {
    t.detection = true;
    t.box = *u.box;
    // A detected target reuses its step-2 position; a tracked or merged box is located anew.
    const measure::Position3D p =
        u.candidate >= 0 && u.parts == 1 ? r.positions[std::size_t(u.candidate)] : locate(t.box);
    t.score = u.candidate >= 0 ? r.detections[std::size_t(u.candidate)].score : 0.f;
    t.depth_ok = p.depth_ok;
    t.cut = p.cut_by_border;
    t.x = p.xyz.x(), t.y = p.xyz.y(), t.z = p.xyz.z();
    t.width = p.width_m, t.height = p.height_m;
    // 5. orient
    orient_target(frame, depth_m, r);
  }
  r.timer.add("orient", lap());
  // 6. the message is r.target
  return r;
}

Config load_config(const std::string& preset, const ConfigMap& overrides) {
  const auto path = io::find_preset(preset);
  Config cfg;
  apply_config(cfg, io::load_config_map(path), path.string());
  // A preset names its model relative to itself; a --set path is the user's, relative to where they are.
  cfg.detector.cnn_model = io::relative_to_preset(path, cfg.detector.cnn_model);
  apply_config(cfg, overrides, "--set");
  cfg.validate(path.string());
  return cfg;
}

}  // namespace cropsight::pipeline::potato
