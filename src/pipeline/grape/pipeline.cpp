// The grape pipeline's composition (see grape/pipeline.hpp): one call per step of the paper,
// then the cut point on the labelled peduncle.
#include "cropsight/pipeline/grape/pipeline.hpp"

#include "cropsight/core/timer.hpp"

#include <cmath>
#include <limits>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/pca.hpp"
#include "cropsight/segmentation/euclidean_clustering.hpp"

namespace cropsight::pipeline::grape {

void Config::validate(const std::string& where) const {
  check_config(*this, where);  // every range, keys named with their section ("roi.z_max")
  roi.validate(where);         // and the rules between roi's fields
}

std::optional<CutPoint> grape_cut_point(const Cloud& cloud, const CutPointConfig& cfg) {
  check_config(cfg, "grape cut point config");
  if (cloud.labels.size() != cloud.size()) throw Error("grape cut point", "the cloud has no labels");
  std::vector<Eigen::Vector3f> peduncle;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (cloud.labels[i] == cfg.peduncle_label) peduncle.push_back(cloud.points[i]);
  if (peduncle.size() < std::size_t(cfg.min_points)) return std::nullopt;
  segmentation::EuclideanClusterConfig ecfg;
  ecfg.tolerance = float(cfg.cluster_tolerance);
  ecfg.min_size = cfg.min_points;  // smaller clusters can never be the answer
  ecfg.max_size = std::numeric_limits<int>::max();
  const auto clusters = segmentation::euclidean_clusters(peduncle, ecfg);
  const Segment* best = nullptr;
  for (const auto& c : clusters)  // ordered by smallest member index: the first of a tie wins
    if (!best || c.size() > best->size()) best = &c;
  if (!best) return std::nullopt;
  const auto& idx = best->indices;
  const auto p = geometry::pca(idx.size(), [&](std::size_t i) { return peduncle[std::size_t(idx[i])].cast<double>(); });
  Eigen::Vector3d axis = p.major();
  // Up in the image is -y in the camera frame; a peduncle hangs the bunch from above, so the
  // axis points from the cut toward the cane. Exactly horizontal: +x, for a deterministic sign.
  if (axis.y() > 0 || (axis.y() == 0 && axis.x() < 0)) axis = -axis;
  CutPoint cut;
  cut.position = p.mean.cast<float>();
  cut.direction = axis.normalized().cast<float>();
  cut.confidence = int(idx.size());
  return cut;
}

std::vector<Detection> grape_detections(const std::vector<Detection2D>& boxes) {
  std::vector<Detection> out;
  out.reserve(boxes.size());
  for (const auto& b : boxes) {
    Detection d;
    const int x0 = int(std::floor(b.x1)), y0 = int(std::floor(b.y1));
    d.box = {x0, y0, int(std::ceil(b.x2)) - x0, int(std::ceil(b.y2)) - y0};
    d.category = b.class_id + 1;
    d.score = b.score;
    d.annotation = long(out.size());
    out.push_back(d);
  }
  return out;
}

Pipeline::Pipeline(Config cfg, Segmenter segmenter, std::unique_ptr<Detector2D> detector, const std::string& where)
    : cfg_(std::move(cfg)), segmenter_(std::move(segmenter)), detector_(std::move(detector)) {
  cfg_.segmenter = segmenter_.config();  // what runs, whatever the caller's config said
  cfg_.validate(where);
}

Pipeline::~Pipeline() = default;
Pipeline::Pipeline(Pipeline&&) noexcept = default;
Pipeline& Pipeline::operator=(Pipeline&&) noexcept = default;

FrameResult Pipeline::process(const RgbdFrame& frame) {
  if (!detector_) throw Error("grape pipeline", "no detector: give the boxes (process(frame, detections))");
  if (frame.color.empty()) throw Error("grape pipeline", "the frame has no colour image (the detector needs one)");
  // Step 1: bunch and peduncle boxes.
  Stopwatch watch;
  std::vector<Detection> boxes = grape_detections(detector_->detect(DetectorInput{&frame.color, nullptr}));
  const double detect_ms = watch.ms();
  FrameResult r = process(frame, boxes);
  r.timer.add("detect", detect_ms);
  return r;
}

FrameResult Pipeline::process(const RgbdFrame& frame, const std::vector<Detection>& detections) const {
  // The segmenter's features include colour: a cloud without it would be labelled from zeros.
  if (frame.color.empty()) throw Error("grape pipeline", "the frame has no colour image (the segmenter needs one)");
  if (frame.color.width != frame.depth.width || frame.color.height != frame.depth.height)
    throw Error("grape pipeline", "colour and depth images differ in size");
  FrameResult r;
  r.detections = detections;
  // Steps 2-4: ROIs (Eq. 1, merged), their coloured clouds (Algorithm 1), normals, unit sphere.
  RoiFrame rois;
  {
    auto t = r.timer.scope("roi");
    rois = grape_roi_clouds(frame.depth, frame.color, frame.camera, detections, cfg_.roi);
  }
  r.outside = std::move(rois.outside);
  for (auto& roi : rois.rois) {
    Bunch b;
    b.roi = roi.box;
    // Step 5: semantic segmentation, on the unit-sphere cloud the models are trained on.
    b.cloud = std::move(roi.cloud);
    {
      auto t = r.timer.scope("segment");
      b.cloud.labels = segmenter_.segment(b.cloud);
    }
    // Back to metres (normals are unchanged by a uniform scale and a shift).
    for (auto& p : b.cloud.points) p = p * roi.scale + roi.centroid;
    // Step 6: where to cut.
    auto t = r.timer.scope("cut_point");
    b.cut_point = grape_cut_point(b.cloud, cfg_.cut_point);
    r.bunches.push_back(std::move(b));
  }
  return r;
}

}  // namespace cropsight::pipeline::grape
