#include "cropsight/pipeline/broccoli/detector.hpp"

#include <algorithm>
#include <utility>

#include "cropsight/pipeline/broccoli/steps/cnn_proposals.hpp"
#include "cropsight/pipeline/broccoli/steps/crease_split.hpp"
#include "cropsight/pipeline/broccoli/steps/head_completion.hpp"

namespace cropsight::pipeline::broccoli {

namespace {
// The config is checked before any step is made from it.
DetectorConfig validated(DetectorConfig cfg) {
  cfg.validate("config");
  return cfg;
}

// OES segments without normals unless crease edges need the curvature: the normals are then
// computed only for the pixels of the kept segments, the only ones the features read.
bool lazy_normals(const DetectorConfig& cfg) {
  return cfg.pipeline == Variant::oes && !(cfg.edges.high_curvature_threshold > 0.0f);
}
}  // namespace

Detector::Detector(DetectorConfig cfg)
    : cfg_(validated(std::move(cfg))),
      cloud_(cfg_.depth, cfg_.denoise, cfg_.range, cfg_.oes),
      normals_(cfg_.normals, lazy_normals(cfg_)),
      edges_(cfg_.edges, cfg_.pipeline == Variant::oes),
      clustering_(cfg_.pipeline, cfg_.org, cfg_.fec, cfg_.outliers),
      description_(cfg_.features, cfg_.feature_options, cfg_.detection.min_normal_points,
                   cfg_.detection.split_oversized_above),
      classification_(cfg_.detection.score_margin) {
  const DetectionConfig& dc = cfg_.detection;
  // The crease split reads the OES thresholds and label image.
  if (dc.split_concave_angle_deg > 0.0f && cfg_.pipeline == Variant::oes)
    refiners_.push_back(std::make_unique<steps::CreaseSplit>(dc, description_, classification_));
  if (dc.grow_tolerance > 0.0f)
    refiners_.push_back(
        std::make_unique<steps::HeadCompletion>(segmentation::SegmentGrowthOptions{dc.grow_tolerance, dc.grow_radius}));
  if (!cfg_.cnn.model.empty()) refiners_.push_back(std::make_unique<steps::CnnProposals>(cfg_.cnn, classification_));
}

Detector::~Detector() = default;

void Detector::set_model(std::shared_ptr<const learning::Model> model, const std::string& where) {
  if (model) {
    learning::require_compatible(model->info, kBroccoliTask, config_name(cfg_.pipeline), cfg_.feature_names(),
                                 int(description_.dimension()), where);
  }
  classification_.set_model(std::move(model));
}

std::span<const Candidate> Detector::process(const RgbdFrame& frame) {
  steps::FrameState& s = state_;
  s.conditions = cloud_.run(frame, s.cloud, timer_);
  normals_.before_clustering(s.cloud, timer_);
  const std::vector<std::uint8_t>& edges = edges_.run(s.cloud, timer_);
  std::vector<Segment> segments = clustering_.run(s.cloud, edges, s.conditions.oes, s.owners, timer_);
  normals_.after_clustering(s.cloud, s.owners, timer_);
  description_.run(segments, s.cloud, s.candidates, timer_);
  classification_.run(s.candidates, timer_);
  for (const auto& refiner : refiners_) refiner->refine(frame, s, timer_);
  return s.candidates.active();
}

std::vector<Detection> Detector::detections() const {
  std::vector<Detection> out;
  for (const Candidate& c : state_.candidates.active()) {
    if (!c.head) continue;
    Detection d;
    d.score = c.score;
    d.label = 1;
    d.centroid = c.segment.centroid;
    d.box = c.segment.box;
    d.indices = c.segment.indices;
    out.push_back(std::move(d));
  }
  std::stable_sort(out.begin(), out.end(), [](const Detection& a, const Detection& b) { return a.score > b.score; });
  return out;
}

}  // namespace cropsight::pipeline::broccoli
