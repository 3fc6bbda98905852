// The target selection and tracking state machine (see target_tracker.hpp).
#include "cropsight/tracking/target_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cropsight::tracking {

TargetTracker::TargetTracker(TargetTrackerConfig cfg, std::unique_ptr<VisualTracker> visual)
    : cfg_(cfg), visual_(visual ? std::move(visual) : make_visual_tracker(cfg.visual_tracker)) {
  check_config(cfg_, "target tracker");
}

TargetTracker::~TargetTracker() = default;

void TargetTracker::reset() {
  has_target_ = false;
  target_id_ = 0;
  frames_tracked_ = 0;
  visual_started_ = false;
  have_last_image_ = false;
}

int TargetTracker::select(const std::vector<TargetCandidate>& candidates) const {
  int best = -1;
  for (int i = 0; i < int(candidates.size()); ++i) {
    const auto& c = candidates[std::size_t(i)];
    if (!c.ripe || !c.depth_ok) continue;
    if (best < 0 || c.distance_m < candidates[std::size_t(best)].distance_m) best = i;
  }
  return best;
}

void TargetTracker::move_to(const Detection2D& box, bool fresh) {
  // Constant velocity of the box centre between consecutive frames, at most half the box gate per
  // axis, so that the gate around the prediction still holds the last centre (a split box or a
  // jittery detection cannot throw the prediction off the target).
  vu_ = vv_ = 0;
  if (!fresh && cfg_.predict_motion) {
    const double gu = 0.5 * cfg_.epsilon_box_fraction * box.width(),
                 gv = 0.5 * cfg_.epsilon_box_fraction * box.height();
    vu_ = float(std::clamp(double(box.centre_x() - last_box_.centre_x()), -gu, gu));
    vv_ = float(std::clamp(double(box.centre_y() - last_box_.centre_y()), -gv, gv));
  }
  last_box_ = box;
}

int TargetTracker::associate(const std::vector<TargetCandidate>& candidates) const {
  const float cu = last_box_.centre_x(), cv = last_box_.centre_y();
  const float pu = cu + vu_, pv = cv + vv_;  // predicted centre (the box gate and `closest`)
  int best = -1;
  double best_key = std::numeric_limits<double>::infinity();
  for (int i = 0; i < int(candidates.size()); ++i) {
    const auto& c = candidates[std::size_t(i)];
    const double du = std::abs(c.box.centre_x() - cu), dv = std::abs(c.box.centre_y() - cv);
    if (!(du < cfg_.epsilon_px && dv < cfg_.epsilon_px)) continue;
    const double qu = std::abs(c.box.centre_x() - pu), qv = std::abs(c.box.centre_y() - pv);
    if (cfg_.epsilon_box_fraction > 0 &&
        !(qu < cfg_.epsilon_box_fraction * last_box_.width() && qv < cfg_.epsilon_box_fraction * last_box_.height()))
      continue;
    if (cfg_.max_area_ratio > 0) {
      const double a = c.box.area(), b = last_box_.area();
      if (!(a * cfg_.max_area_ratio >= b && b * cfg_.max_area_ratio >= a)) continue;
    }
    double key = qu * qu + qv * qv;
    if (cfg_.association == TargetAssociation::nearest)
      key = c.depth_ok ? double(c.distance_m) : std::numeric_limits<double>::max();
    if (key < best_key || best < 0) best = i, best_key = key;
  }
  return best;
}

TargetUpdate TargetTracker::detected(const ColorImage* image, const std::vector<TargetCandidate>& candidates, int index,
                                     bool fresh) {
  move_to(candidates[std::size_t(index)].box, fresh);
  frames_tracked_ = 0;
  visual_started_ = false;
  have_last_image_ = image != nullptr && visual_ != nullptr && cfg_.tracking_limit > 0;
  if (have_last_image_) last_image_ = *image;
  TargetUpdate u;
  u.state = TargetState::detected;
  u.target_id = target_id_;
  u.box = last_box_;
  u.candidate = index;
  return u;
}

TargetUpdate TargetTracker::update(const ColorImage* image, const std::vector<TargetCandidate>& candidates) {
  if (!has_target_) {
    const int i = select(candidates);
    if (i < 0) return {};
    has_target_ = true;
    target_id_ = next_id_++;
    return detected(image, candidates, i, true);
  }
  const int i = associate(candidates);
  if (i >= 0) return detected(image, candidates, i, false);

  // No detection continues the target: the visual tracker carries it, within the limit.
  std::optional<Detection2D> box;
  if (frames_tracked_ < cfg_.tracking_limit && image != nullptr && visual_ != nullptr &&
      (visual_started_ || have_last_image_)) {
    if (!visual_started_) {
      visual_->init(last_image_, last_box_);
      visual_started_ = true;
    }
    box = visual_->update(*image);
  }
  if (!box) {
    TargetUpdate u;
    u.state = TargetState::lost;
    u.target_id = target_id_;
    u.frames_tracked = frames_tracked_;
    reset();
    return u;
  }
  ++frames_tracked_;
  move_to(*box, false);
  TargetUpdate u;
  u.state = TargetState::tracked;
  u.target_id = target_id_;
  u.box = box;
  u.frames_tracked = frames_tracked_;
  return u;
}

}  // namespace cropsight::tracking
