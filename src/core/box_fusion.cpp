#include "cropsight/core/box_fusion.hpp"

#include <algorithm>

#include "cropsight/core/error.hpp"

namespace cropsight {

namespace {

struct Cluster {
  std::vector<std::size_t> detectors;     // which detector each member came from
  double score_sum = 0, weights = 0;      // sum of the scores, of the corner weights
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;  // weighted corner sums
  Detection2D fused;

  void add(const Detection2D& d, std::size_t detector) {
    detectors.push_back(detector);
    // A box of score 0 still counts: weight it a little so the mean stays defined.
    const double w = std::max<double>(d.score, 1e-6);
    score_sum += d.score, x1 += w * d.x1, y1 += w * d.y1, x2 += w * d.x2, y2 += w * d.y2;
    weights += w;
    fused.class_id = d.class_id;
    fused.x1 = float(x1 / weights), fused.y1 = float(y1 / weights);
    fused.x2 = float(x2 / weights), fused.y2 = float(y2 / weights);
  }
};

}  // namespace

std::vector<Detection2D> weighted_boxes_fusion(const std::vector<std::vector<Detection2D>>& per_detector,
                                               const BoxFusionConfig& cfg) {
  struct Ranked {
    Detection2D box;
    std::size_t detector;
  };
  std::vector<Ranked> all;
  for (std::size_t k = 0; k < per_detector.size(); ++k)
    for (const auto& d : per_detector[k]) all.push_back({d, k});
  // Stable: equal scores keep the detectors' order, so the result does not depend on the sort.
  std::stable_sort(all.begin(), all.end(), [](const Ranked& a, const Ranked& b) { return a.box.score > b.box.score; });

  std::vector<Cluster> clusters;
  for (const auto& r : all) {
    Cluster* best = nullptr;
    float best_iou = float(cfg.iou_threshold);
    for (auto& c : clusters) {
      if (c.fused.class_id != r.box.class_id) continue;
      if (std::find(c.detectors.begin(), c.detectors.end(), r.detector) != c.detectors.end()) continue;
      const float v = iou(r.box, c.fused);
      if (v >= best_iou) best = &c, best_iou = v;
    }
    if (!best) best = &clusters.emplace_back();
    best->add(r.box, r.detector);
  }

  std::vector<Detection2D> out;
  out.reserve(clusters.size());
  const double n = double(std::max<std::size_t>(1, per_detector.size()));
  for (const auto& c : clusters) {
    Detection2D d = c.fused;
    d.score = float(c.score_sum / n);
    out.push_back(d);
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const Detection2D& a, const Detection2D& b) { return a.score > b.score; });
  return out;
}

FusedDetector::FusedDetector(std::vector<std::unique_ptr<Detector2D>> detectors, BoxFusionConfig cfg)
    : detectors_(std::move(detectors)), cfg_(cfg) {
  if (detectors_.empty()) throw Error("fused detector", "needs at least one detector");
  for (const auto& d : detectors_)
    if (!d) throw Error("fused detector", "a detector is missing");
  const auto names = detectors_.front()->class_names();
  for (const auto& d : detectors_)
    if (d->class_names() != names)
      throw Error("fused detector",
                  "the detectors name different classes; fusion needs the same classes in the same order");
}

std::vector<Detection2D> FusedDetector::detect(const DetectorInput& in) {
  std::vector<std::vector<Detection2D>> per_detector;
  per_detector.reserve(detectors_.size());
  for (auto& d : detectors_) per_detector.push_back(d->detect(in));
  return weighted_boxes_fusion(per_detector, cfg_);
}

std::vector<std::string> FusedDetector::class_names() const { return detectors_.front()->class_names(); }

}  // namespace cropsight
