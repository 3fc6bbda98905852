#include "cropsight/tracking/head_mapper.hpp"

#include <algorithm>
#include <limits>

#include "cropsight/core/error.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "tracking/order_statistic.hpp"

namespace cropsight::tracking {

namespace {
/// Centroid (camera frame) of the points within `cap` metres of depth of the head's top. The top
/// is the 2nd percentile of depth, so that a few flying pixels in front of the head do not set it.
/// Falls back to the centroid of all valid points when fewer than 3 are in the cap.
Eigen::Vector3f top_centroid(const OrganizedCloud& cloud, const std::vector<int>& indices, double cap,
                             std::vector<float>& depth, std::vector<float>& scratch) {
  depth.clear();
  for (int i : indices)
    if (cloud.valid(std::size_t(i))) depth.push_back(cloud.z[std::size_t(i)]);
  Eigen::Vector3d sum_all = Eigen::Vector3d::Zero(), sum_cap = Eigen::Vector3d::Zero();
  if (depth.empty()) return Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
  const std::size_t k = std::size_t(0.02 * double(depth.size() - 1));
  const double limit = double(kth_smallest(depth, k, scratch)) + cap;
  int n_all = 0, n_cap = 0;
  for (int i : indices) {
    const auto u = std::size_t(i);
    if (!cloud.valid(u)) continue;
    const Eigen::Vector3d p = cloud.point(u).cast<double>();
    sum_all += p;
    ++n_all;
    if (p.z() <= limit) sum_cap += p, ++n_cap;
  }
  return (n_cap >= 3 ? sum_cap / n_cap : sum_all / n_all).cast<float>();
}
}  // namespace

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
  const double position_cap_m = filter_.config().position_cap_m;
  for (std::size_t k = 0; k < detections.size(); ++k) {
    const Box2D& b = detections[k].box;
    obs[k].centroid = position_cap_m > 0 ? top_centroid(cloud, detections[k].indices, position_cap_m, depth_scratch_, select_scratch_)
                                         : detections[k].centroid;
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
    m.centroid = obs[k].centroid;
    m.field_position = filter_.transform().to_field(a.camera_position, obs[k].centroid);
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
  // Detections of a track merged into a mapped head belong to it (kept ids are always the id of
  // the group's first track, so there are no chains).
  for (const auto& [absorbed, kept] : filter_.merged_ids())
    if (confirmed_.count(kept)) confirmed_.insert(absorbed);
  return map_;
}

float HeadMapper::filtered_score(const MeasuredDetection& d) const {
  return confirmed(d.track_id) ? d.score + kConfirmedBonus : d.score;
}

}  // namespace cropsight::tracking
