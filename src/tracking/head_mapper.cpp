#include "cropsight/tracking/head_mapper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cropsight/core/camera.hpp"
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
    obs[k].centroid = position_cap_m > 0
                          ? top_centroid(cloud, detections[k].indices, position_cap_m, depth_scratch_, select_scratch_)
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
    if (!record_) continue;
    MeasuredDetection m;
    m.frame = frame;
    m.index = int(k);
    m.track_id = a.track_ids[k];
    m.score = detections[k].score;
    m.centroid = obs[k].centroid;
    m.field_position = filter_.transform().to_field(a.camera_position, obs[k].centroid);
    m.size = obs[k].size;
    m.partial = obs[k].partial;
    m.confirmed_online = m.track_id >= 0 && filter_.confirmed_now(m.track_id);
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

std::optional<float> HeadMapper::predicted_score(int track_id) const {
  if (!confirmed(track_id)) return std::nullopt;
  return kConfirmedBonus - 1.0f;
}

float HeadMapper::online_score(const MeasuredDetection& d) {
  return d.confirmed_online ? d.score + kConfirmedBonus : d.score;
}

std::optional<float> HeadMapper::online_predicted_score(const PredictedHead& p) {
  if (!p.confirmed_online) return std::nullopt;
  return kConfirmedBonus - 1.0f;
}

std::vector<PredictedHead> HeadMapper::predict_missed(const OrganizedCloud& cloud,
                                                      const CameraIntrinsics& camera) const {
  std::vector<PredictedHead> out;
  const TemporalFilterConfig& cfg = filter_.config();
  if (!cfg.predict_missed || cloud.empty()) return out;
  if (cloud.width != camera.width || cloud.height != camera.height || !(camera.fx > 0.0) || !(camera.fy > 0.0))
    throw Error("head mapper", "predict_missed: the intrinsics do not match the cloud");
  // The head's position is the centroid of its points within position_cap_m of its top, about half
  // the cap below the apex; the centre of a head of radius ρ lies ρ below the apex along the view.
  const double half_cap = 0.5 * cfg.position_cap_m;
  for (const TrackedHead& h : filter_.tracked()) {
    if (h.missed < 1) continue;  // detected (or started) in this frame
    // ρ: half the running bounding-box width; 5 cm before any whole detection was measured.
    const double rho = h.size_samples > 0 && h.bbox_mm > 0.0 ? 0.0005 * h.bbox_mm : 0.05;
    const Eigen::Vector3d top = filter_.transform().to_camera(filter_.camera_position(), h.position);
    const Eigen::Vector3d c = top + Eigen::Vector3d(0.0, 0.0, rho - half_cap);
    const double r = cfg.predict_radius_scale * rho;
    const double z_near = c.z() - r, z_far = c.z() + r;
    if (!(z_near > 1e-3)) continue;  // behind or at the camera
    // Pixel box of the ball: its x/y extent seen at the nearest and farthest depth.
    auto span = [&](double centre, double f, double principal, int size, int& lo, int& hi) {
      double a = INFINITY, b = -INFINITY;
      for (double z : {z_near, z_far})
        for (double s : {-r, r}) {
          const double px = f * (centre + s) / z + principal;
          a = std::min(a, px), b = std::max(b, px);
        }
      lo = std::max(0, int(std::floor(a))), hi = std::min(size - 1, int(std::ceil(b)));
    };
    int u0, u1, v0, v1;
    span(c.x(), camera.fx, camera.cx, cloud.width, u0, u1);
    span(c.y(), camera.fy, camera.cy, cloud.height, v0, v1);
    if (u0 > u1 || v0 > v1) continue;  // outside the image
    PredictedHead p;
    p.track_id = h.id;
    p.centre = c.cast<float>();
    p.radius_m = float(r);
    p.confirmed_online = filter_.confirmed_now(h);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    const double r2 = r * r, z_max = c.z() + half_cap;  // the visible (upper) half, and the cap's slack
    for (int v = v0; v <= v1; ++v)
      for (int u = u0; u <= u1; ++u) {
        const std::size_t i = std::size_t(cloud.index(u, v));
        const double z = cloud.z[i];
        if (!(z <= z_max)) continue;  // also NaN
        const Eigen::Vector3d q(cloud.x[i], cloud.y[i], z);
        if ((q - c).squaredNorm() > r2) continue;
        p.indices.push_back(int(i));
        sum += q;
      }
    if (int(p.indices.size()) < cfg.predict_min_points) continue;
    p.centroid = (sum / double(p.indices.size())).cast<float>();
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace cropsight::tracking
