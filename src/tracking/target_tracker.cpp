// The target selection and tracking state machine (see target_tracker.hpp).
#include "cropsight/tracking/target_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cropsight::tracking {

TargetTracker::TargetTracker(TargetTrackerConfig cfg, std::unique_ptr<VisualTracker> visual)
    : cfg_(cfg), visual_(visual ? std::move(visual) : make_visual_tracker(cfg.visual_tracker, cfg.csrt)) {
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

namespace {
float intersection(const Detection2D& a, const Detection2D& b) {
  const float w = std::min(a.x2, b.x2) - std::max(a.x1, b.x1), h = std::min(a.y2, b.y2) - std::max(a.y1, b.y1);
  return w > 0 && h > 0 ? w * h : 0.f;
}
Detection2D unite(Detection2D a, const Detection2D& b) {
  a.x1 = std::min(a.x1, b.x1), a.y1 = std::min(a.y1, b.y1), a.x2 = std::max(a.x2, b.x2), a.y2 = std::max(a.y2, b.y2);
  a.score = std::max(a.score, b.score);
  return a;
}
}  // namespace

void TargetTracker::move_to(const Detection2D& box, bool fresh) {
  // Constant velocity of the box centre between consecutive frames, at most a quarter of the box
  // per axis, so that the predicted box still overlaps the last one by more than half (a split
  // box or a jittery detection cannot throw the prediction off the target).
  vu_ = vv_ = 0;
  if (!fresh && cfg_.predict_motion) {
    const double gu = 0.25 * box.width(), gv = 0.25 * box.height();
    vu_ = float(std::clamp(double(box.centre_x() - last_box_.centre_x()), -gu, gu));
    vv_ = float(std::clamp(double(box.centre_y() - last_box_.centre_y()), -gv, gv));
  }
  last_box_ = box;
}

Detection2D TargetTracker::predicted() const {
  Detection2D p = last_box_;
  p.x1 += vu_, p.x2 += vu_, p.y1 += vv_, p.y2 += vv_;
  return p;
}

bool TargetTracker::in_gate(const Detection2D& box, const Detection2D& pred) const {
  const double du = std::abs(box.centre_x() - last_box_.centre_x()),
               dv = std::abs(box.centre_y() - last_box_.centre_y());
  if (!(du < cfg_.epsilon_px && dv < cfg_.epsilon_px)) return false;  // the paper's rule
  const double a = box.area(), b = last_box_.area();
  if (cfg_.min_overlap > 0 && !(intersection(box, pred) >= cfg_.min_overlap * std::min(a, b))) return false;
  if (cfg_.max_area_ratio > 0 && !(a * cfg_.max_area_ratio >= b && b * cfg_.max_area_ratio >= a)) return false;
  return true;
}

int TargetTracker::associate(const std::vector<TargetCandidate>& candidates) const {
  const Detection2D pred = predicted();
  int best = -1;
  double best_key = std::numeric_limits<double>::infinity();
  for (int i = 0; i < int(candidates.size()); ++i) {
    const auto& c = candidates[std::size_t(i)];
    if (!in_gate(c.box, pred)) continue;
    const double qu = c.box.centre_x() - pred.centre_x(), qv = c.box.centre_y() - pred.centre_y();
    double key = qu * qu + qv * qv;
    if (cfg_.association == TargetAssociation::nearest)
      key = c.depth_ok ? double(c.distance_m) : std::numeric_limits<double>::max();
    if (key < best_key || best < 0) best = i, best_key = key;
  }
  return best;
}

Detection2D TargetTracker::merge_parts(const std::vector<TargetCandidate>& candidates, int index, int& parts) const {
  // A root across the potato splits its detection: the other detections that lie mostly inside the
  // predicted box are parts of the same potato, as long as the whole stays within the area gate.
  Detection2D box = candidates[std::size_t(index)].box;
  parts = 1;
  if (!cfg_.merge_parts) return box;
  const Detection2D pred = predicted();
  for (int j = 0; j < int(candidates.size()); ++j) {
    const Detection2D& c = candidates[std::size_t(j)].box;
    if (j == index || !(intersection(c, pred) >= 0.5f * c.area())) continue;
    const Detection2D u = unite(box, c);
    if (cfg_.max_area_ratio > 0 && u.area() > cfg_.max_area_ratio * last_box_.area()) continue;
    box = u;
    ++parts;
  }
  return box;
}

TargetUpdate TargetTracker::detected(const ColorImage* image, const std::vector<TargetCandidate>& candidates, int index,
                                     bool fresh) {
  int parts = 1;
  const Detection2D box = fresh ? candidates[std::size_t(index)].box : merge_parts(candidates, index, parts);
  move_to(box, fresh);
  frames_tracked_ = 0;
  visual_started_ = false;
  have_last_image_ = image != nullptr && visual_ != nullptr && cfg_.tracking_limit > 0;
  if (have_last_image_) last_image_ = *image;
  TargetUpdate u;
  u.state = TargetState::detected;
  u.target_id = target_id_;
  u.box = last_box_;
  u.candidate = index;
  u.parts = parts;
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
