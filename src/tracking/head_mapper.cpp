#include "cropsight/tracking/head_mapper.hpp"

#include "cropsight/core/error.hpp"
#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::tracking {

void HeadMapperConfig::apply(const ConfigMap& values, const std::string& where) {
  apply_config(sizing, values, where, "sizing.");
  apply_config(tracking, values, where, "tracking.");
}

HeadMapper::HeadMapper(const HeadMapperConfig& cfg) : sizer_(cfg.sizing), filter_(cfg.tracking, sizer_) {}

FrameAssociation HeadMapper::add_frame(int frame, const OrganizedCloud& cloud, std::vector<Detection>& detections,
                                       const std::optional<Eigen::Vector3d>& camera_position) {
  if (finished_) throw Error("frame " + std::to_string(frame), "head mapper already finished");
  std::vector<HeadObservation> obs(detections.size());
  const int margin = filter_.config().border_margin_px;
  for (std::size_t k = 0; k < detections.size(); ++k) {
    const Box2D& b = detections[k].box;
    obs[k].centroid = detections[k].centroid;
    obs[k].score = detections[k].score;
    obs[k].partial = margin >= 0 && (b.x <= margin || b.y <= margin || b.x + b.width >= cloud.width - margin ||
                                     b.y + b.height >= cloud.height - margin);
    // A head cut by the border is not measured: its width would be the visible part's.
    if (!obs[k].partial) obs[k].size = sizer_.measure(cloud, detections[k].indices);
    detections[k].size_m = obs[k].size.valid ? float(obs[k].size.diameter_mm / 1000.0) : 0.0f;
  }
  FrameAssociation a = filter_.update(frame, obs, camera_position);
  for (std::size_t k = 0; k < detections.size(); ++k) {
    detections[k].track_id = a.track_ids[k];
    MeasuredDetection m;
    m.frame = frame;
    m.index = int(k);
    m.track_id = a.track_ids[k];
    m.score = detections[k].score;
    m.centroid = detections[k].centroid;
    m.field_position = filter_.transform().to_field(a.camera_position, detections[k].centroid);
    m.size = obs[k].size;
    m.partial = obs[k].partial;
    measured_.push_back(m);
  }
  return a;
}

const std::vector<TrackedHead>& HeadMapper::finish() {
  if (finished_) throw Error("head mapper", "finish() called twice");
  finished_ = true;
  map_ = filter_.finish();
  for (const auto& h : map_) confirmed_.insert(h.id);
  return map_;
}

float HeadMapper::filtered_score(const MeasuredDetection& d) const {
  return confirmed(d.track_id) ? d.score + kConfirmedBonus : d.score;
}

}  // namespace cropsight::tracking
