// Temporal filter of Kusumam et al. §4.5 (see the header for the algorithm). The sets are small
// (tens of heads), so association is a plain all-pairs search: cheaper than any spatial index at
// this size, and exact.
#include "cropsight/tracking/temporal_filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "cropsight/core/error.hpp"

namespace cropsight::tracking {

namespace {

struct Pair {
  double d;
  int det, head;
};

// One-to-one association, closest pairs first, pairs farther than `radius` excluded.
// Returns per detection the index into `heads` or -1.
std::vector<int> associate(const std::vector<Eigen::Vector3d>& det, const std::vector<TrackedHead>& heads,
                           const Eigen::Vector3d& shift, double radius, std::vector<Pair>& scratch) {
  scratch.clear();
  const double r2 = radius * radius;
  for (int j = 0; j < int(det.size()); ++j)
    for (int i = 0; i < int(heads.size()); ++i) {
      const double d2 = (heads[std::size_t(i)].position - (det[std::size_t(j)] + shift)).squaredNorm();
      if (d2 <= r2) scratch.push_back({d2, j, i});
    }
  std::sort(scratch.begin(), scratch.end(), [](const Pair& a, const Pair& b) {
    return a.d < b.d || (a.d == b.d && (a.det < b.det || (a.det == b.det && a.head < b.head)));
  });
  std::vector<int> out(det.size(), -1);
  std::vector<char> used(heads.size(), 0);
  for (const auto& p : scratch) {
    if (out[std::size_t(p.det)] >= 0 || used[std::size_t(p.head)]) continue;
    out[std::size_t(p.det)] = p.head;
    used[std::size_t(p.head)] = 1;
  }
  return out;
}

struct Score {
  int n = 0;
  double residual = 0.0;
};

Score score_of(const std::vector<int>& a, const std::vector<Eigen::Vector3d>& det,
               const std::vector<TrackedHead>& heads, const Eigen::Vector3d& shift) {
  Score s;
  for (std::size_t j = 0; j < a.size(); ++j)
    if (a[j] >= 0) {
      ++s.n;
      s.residual += (heads[std::size_t(a[j])].position - (det[j] + shift)).norm();
    }
  return s;
}

}  // namespace

TemporalFilter::TemporalFilter(const TemporalFilterConfig& cfg, const measure::HeadSizer& sizer)
    : cfg_(cfg), sizer_(sizer), transform_(FieldTransform::parse(cfg.camera_to_field)) {
  check_config(cfg_, "tracking", "tracking.");  // the ranges declared in TemporalFilterConfig::visit
  if (cfg_.initial_velocity.size() != 3)
    throw Error("tracking.initial_velocity", "expects three numbers [x, y, z] (m/frame)");
  v_c_ = Eigen::Vector3d(cfg_.initial_velocity[0], cfg_.initial_velocity[1], cfg_.initial_velocity[2]);
}

TrackedHead TemporalFilter::new_head(int frame, const Eigen::Vector3d& p) {
  TrackedHead h;
  h.id = next_id_++;
  h.score = cfg_.initial_score;
  h.first_frame = h.last_frame = frame;
  h.position = p;
  if (!has_velocity_) births_.push_back({h.id, frame, x_c_});
  return h;
}

void TemporalFilter::touch(TrackedHead& h, int frame) const {
  h.score += cfg_.score_increment;
  h.last_frame = frame;
  h.missed = 0;
}

void TemporalFilter::add_sample(TrackedHead& h, const Eigen::Vector3d& p, const HeadObservation& d) const {
  const double n = double(h.whole_frames());  // 0 for a head placed by partial views: they are replaced
  h.position = (h.position * n + p) / (n + 1.0);
  h.mean_detection_score = (h.mean_detection_score * n + double(d.score)) / (n + 1.0);
  h.frames_seen += 1;
  if (d.size.valid) {
    const double m = double(h.size_samples);
    h.bbox_mm = (h.bbox_mm * m + d.size.bbox_mm) / (m + 1.0);
    h.hull_mm = (h.hull_mm * m + d.size.hull_mm) / (m + 1.0);
    h.size_samples += 1;
    h.diameter_mm = sizer_.corrected(h.bbox_mm, h.hull_mm);
    h.harvestable = sizer_.harvestable(h.diameter_mm);
  }
}

// What one update() works on, passed from step to step.
struct TemporalFilter::Step {
  int frame = 0;
  int steps = 0;  // frames since the previous update (skipped frames advance the prediction)
  Eigen::Vector3d x_prev = Eigen::Vector3d::Zero(), x_pred = Eigen::Vector3d::Zero();
  std::vector<int> used;             // indices of the whole detections the tracker takes
  std::vector<Eigen::Vector3d> rel;  // their offsets from the camera, field axes
  std::vector<Eigen::Vector3d> det;  // their field positions for the predicted camera
  std::vector<int> assoc;            // per used detection: index into tracked_, or -1
  std::vector<char> seen;            // per head of T before this frame: detected now
  std::size_t old_count = 0;         // heads in T before this frame
  FrameAssociation out;
};

FrameAssociation TemporalFilter::update(int frame, const std::vector<HeadObservation>& detections,
                                        const std::optional<Eigen::Vector3d>& camera_position) {
  const std::string where = "frame " + std::to_string(frame);
  if (finished_) throw Error(where, "temporal filter already finished");
  if (frame <= last_frame_) throw Error(where, "frames must arrive in increasing order");
  if (cfg_.use_poses && !camera_position)
    throw Error(where, "tracking.use_poses is set but the frame has no camera position (poses.csv)");
  Step s;
  s.frame = frame;
  s.out.track_ids.assign(detections.size(), -1);
  s.out.new_track.assign(detections.size(), false);
  predict_camera(camera_position, s);     // 1.
  place_detections(detections, s);        //    D in the field frame
  associate_detections(s);                // 2.-3.
  correct_camera(s);                      // 4.
  update_heads(detections, s);            // 5.
  add_partial_detections(detections, s);  //    (extension)
  retire_missed_heads(s);                 // 6.
  s.out.camera_position = x_c_;
  s.out.camera_velocity = v_c_;
  return s.out;
}

// 1. Prediction of the camera position.
void TemporalFilter::predict_camera(const std::optional<Eigen::Vector3d>& camera_position, Step& s) {
  s.x_prev = x_c_;
  s.steps = started_ ? s.frame - last_frame_ : 0;
  if (cfg_.use_poses) {
    s.x_pred = *camera_position;
  } else if (!started_) {
    s.x_pred = (cfg_.anchor_first_pose && camera_position) ? *camera_position : Eigen::Vector3d::Zero();
  } else {
    s.x_pred = x_c_ + double(s.steps) * v_c_;
  }
  if (!started_) first_frame_ = s.frame, x_first_ = s.x_pred;
  started_ = true;
  last_frame_ = s.frame;
}

// Whole detections in the field frame relative to the predicted camera position.
void TemporalFilter::place_detections(const std::vector<HeadObservation>& detections, Step& s) const {
  for (int j = 0; j < int(detections.size()); ++j) {
    const auto& d = detections[std::size_t(j)];
    if (!(double(d.score) >= cfg_.min_detection_score) || !d.centroid.allFinite() || d.partial) continue;
    s.used.push_back(j);
    s.rel.push_back(transform_.rotation * d.centroid.cast<double>());
  }
  s.det.resize(s.rel.size());
  for (std::size_t k = 0; k < s.rel.size(); ++k) s.det[k] = s.x_pred + s.rel[k];
}

// 2.-3. Association, with the shift vote when the prediction leaves pairs unexplained.
void TemporalFilter::associate_detections(Step& s) const {
  std::vector<Pair> scratch;
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
  s.assoc = associate(s.det, tracked_, shift, cfg_.association_radius_m, scratch);
  if (!cfg_.motion_search || cfg_.use_poses || s.det.empty() || tracked_.empty()) return;
  Score best = score_of(s.assoc, s.det, tracked_, shift);
  const std::size_t possible = std::min(s.det.size(), tracked_.size());
  if (std::size_t(best.n) >= possible) return;
  // Once the velocity is known, a vote needs motion_search_min_pairs pairs: with one detection
  // (often a false one) some shift within the radius always pairs it with some head, and that
  // jump, taken into the velocity, derails every later frame (a spain pass: 0.25 m at frame 18).
  const int needed = has_velocity_ ? cfg_.motion_search_min_pairs : 1;
  if (int(possible) < needed) return;
  s.out.motion_searched = true;
  const double r2 = cfg_.motion_search_radius_m * cfg_.motion_search_radius_m;
  bool searched = false;
  for (const auto& h : tracked_)
    for (const auto& p : s.det) {
      const Eigen::Vector3d shift_try = h.position - p;
      if (shift_try.squaredNorm() > r2) continue;
      auto a = associate(s.det, tracked_, shift_try, cfg_.association_radius_m, scratch);
      const Score sc = score_of(a, s.det, tracked_, shift_try);
      // Strictly more pairs than the prediction explains; among shifts with as many pairs the
      // smallest residual wins.
      if (sc.n < needed) continue;
      if (sc.n > best.n || (searched && sc.n == best.n && sc.residual < best.residual)) {
        searched = true;
        best = sc;
        s.assoc = std::move(a);
      }
    }
}

// 4. Camera correction by the mean displacement of the associated pairs (heads placed by partial
// detections only are off-centre: they do not move the camera).
void TemporalFilter::correct_camera(Step& s) {
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();
  int n_assoc = 0;
  for (std::size_t k = 0; k < s.det.size(); ++k)
    if (s.assoc[k] >= 0 && tracked_[std::size_t(s.assoc[k])].whole_frames() > 0) {
      delta += tracked_[std::size_t(s.assoc[k])].position - s.det[k];
      ++n_assoc;
    }
  if (cfg_.use_poses) {
    x_c_ = s.x_pred;
  } else {
    x_c_ = n_assoc ? Eigen::Vector3d(s.x_pred + delta / double(n_assoc)) : s.x_pred;
  }
  if (s.steps > 0 && (n_assoc > 0 || cfg_.use_poses)) {
    if (!has_velocity_ && !cfg_.use_poses && cfg_.startup_constant_velocity)
      start_constant_velocity(s);
    else
      v_c_ = (x_c_ - s.x_prev) / double(s.steps);
    has_velocity_ = true;
    births_.clear();
  }
  s.out.associated = n_assoc;
}

// 4. at the first association (startup_constant_velocity). Until now the camera estimate did not
// move unless a detection was associated, and none was: every head was placed once, at its birth
// frame j, with the camera estimate of that frame. A pair (detection now, head born at j) says how
// far the camera travelled from j to now: (head position - detection offset) - camera(j). Divided
// by the frames between, that is the velocity; pairs are averaged. Constant velocity from the first
// frame then gives the camera now and at every birth frame, and each head born after the first
// frame moves by the difference to the camera it was placed with. Without this, a first head seen
// only cut by the border, then another head, left the whole map one frame's travel behind (a spain
// validation pass: 4 cm, at the edge of the 5 cm map match); a gap of empty frames made the velocity
// the whole gap's travel in one frame.
void TemporalFilter::start_constant_velocity(Step& s) {
  auto birth_of = [&](int id) -> const Birth* {
    for (const auto& b : births_)
      if (b.id == id) return &b;
    return nullptr;
  };
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  int n = 0;
  for (std::size_t k = 0; k < s.det.size(); ++k) {
    if (s.assoc[k] < 0) continue;
    const TrackedHead& h = tracked_[std::size_t(s.assoc[k])];
    const Birth* b = birth_of(h.id);
    if (h.whole_frames() == 0 || b == nullptr || b->frame >= s.frame) continue;
    v += (h.position - s.rel[k] - b->camera) / double(s.frame - b->frame);
    ++n;
  }
  if (n == 0) {  // only heads placed by partial views: the plain estimate
    v_c_ = (x_c_ - s.x_prev) / double(s.steps);
    return;
  }
  v_c_ = v / double(n);
  x_c_ = x_first_ + double(s.frame - first_frame_) * v_c_;
  for (auto* set : {&tracked_, &mapped_})
    for (auto& h : *set)
      if (const Birth* b = birth_of(h.id)) h.position += x_first_ + double(b->frame - first_frame_) * v_c_ - b->camera;
}

// 5. Score and running averages of associated heads; unassociated detections start heads.
void TemporalFilter::update_heads(const std::vector<HeadObservation>& detections, Step& s) {
  s.seen.assign(tracked_.size(), 0);
  s.old_count = tracked_.size();
  for (std::size_t k = 0; k < s.det.size(); ++k) {
    const std::size_t j = std::size_t(s.used[k]);
    const auto& d = detections[j];
    const Eigen::Vector3d p = x_c_ + s.rel[k];
    if (s.assoc[k] >= 0) {
      auto& h = tracked_[std::size_t(s.assoc[k])];
      touch(h, s.frame);
      add_sample(h, p, d);
      s.seen[std::size_t(s.assoc[k])] = 1;
      s.out.track_ids[j] = h.id;
    } else {
      TrackedHead h = new_head(s.frame, p);
      add_sample(h, p, d);
      h.position = p;
      tracked_.push_back(h);
      s.out.track_ids[j] = h.id;
      s.out.new_track[j] = true;
    }
  }
}

// Partial detections (see the header): the nearest head within partial_association_radius_m that
// this frame's detections have not claimed; with partial_tracks they keep it alive and raise its
// score, or start a head.
void TemporalFilter::add_partial_detections(const std::vector<HeadObservation>& detections, Step& s) {
  const double pr2 = cfg_.partial_association_radius_m * cfg_.partial_association_radius_m;
  for (std::size_t j = 0; j < detections.size(); ++j) {
    const auto& d = detections[j];
    if (!d.partial || !(double(d.score) >= cfg_.min_detection_score) || !d.centroid.allFinite()) continue;
    const Eigen::Vector3d p = transform_.to_field(x_c_, d.centroid);
    double best = pr2;
    int nearest = -1;
    for (std::size_t i = 0; i < tracked_.size(); ++i) {
      if (cfg_.partial_tracks && i < s.seen.size() && s.seen[i]) continue;
      if (cfg_.partial_tracks && i >= s.old_count) continue;  // started by this frame
      const double d2 = (tracked_[i].position - p).squaredNorm();
      if (d2 <= best) best = d2, nearest = int(i);
    }
    if (!cfg_.partial_tracks) {
      if (nearest >= 0) s.out.track_ids[j] = tracked_[std::size_t(nearest)].id;
      continue;
    }
    if (nearest >= 0) {
      auto& h = tracked_[std::size_t(nearest)];
      touch(h, s.frame);
      if (h.whole_frames() == 0) {  // placed by partial detections only: average them
        const double m = double(h.partial_frames);
        h.position = (h.position * m + p) / (m + 1.0);
        h.mean_detection_score = (h.mean_detection_score * m + double(d.score)) / (m + 1.0);
      }
      h.partial_frames += 1;
      h.frames_seen += 1;
      s.seen[std::size_t(nearest)] = 1;
      s.out.track_ids[j] = h.id;
    } else {
      TrackedHead h = new_head(s.frame, p);
      h.mean_detection_score = double(d.score);
      h.partial_frames = h.frames_seen = 1;
      tracked_.push_back(h);
      s.out.track_ids[j] = h.id;
      s.out.new_track[j] = true;
    }
  }
}

// 6. Heads undetected for max_missed_frames frames move to the map.
void TemporalFilter::retire_missed_heads(const Step& s) {
  std::vector<TrackedHead> keep;
  keep.reserve(tracked_.size());
  for (std::size_t i = 0; i < tracked_.size(); ++i) {
    auto& h = tracked_[i];
    if (i < s.old_count && !s.seen[i]) h.missed += std::max(s.steps, 1);
    if (h.missed >= cfg_.max_missed_frames)
      mapped_.push_back(h);
    else
      keep.push_back(h);
  }
  tracked_.swap(keep);
}

void TemporalFilter::absorb(TrackedHead& into, const TrackedHead& later) const {
  // Positions average over whole frames (partial-only heads carry the mean of their partial
  // centroids: they count with their partial frames when neither side has a whole frame).
  const bool whole = into.whole_frames() > 0 || later.whole_frames() > 0;
  const double wa = whole ? into.whole_frames() : into.partial_frames;
  const double wb = whole ? later.whole_frames() : later.partial_frames;
  if (wa + wb > 0) into.position = (into.position * wa + later.position * wb) / (wa + wb);
  const double sa = into.frames_seen, sb = later.frames_seen;
  if (sa + sb > 0)
    into.mean_detection_score = (into.mean_detection_score * sa + later.mean_detection_score * sb) / (sa + sb);
  into.score += later.score;
  into.frames_seen += later.frames_seen;
  into.partial_frames += later.partial_frames;
  into.first_frame = std::min(into.first_frame, later.first_frame);
  into.last_frame = std::max(into.last_frame, later.last_frame);
  const int m = into.size_samples + later.size_samples;
  if (m > 0) {
    into.bbox_mm = (into.bbox_mm * into.size_samples + later.bbox_mm * later.size_samples) / m;
    into.hull_mm = (into.hull_mm * into.size_samples + later.hull_mm * later.size_samples) / m;
    into.size_samples = m;
    into.diameter_mm = sizer_.corrected(into.bbox_mm, into.hull_mm);
    into.harvestable = sizer_.harvestable(into.diameter_mm);
  }
}

void TemporalFilter::merge_lost_and_found() {
  if (!(cfg_.merge_radius_m > 0.0) || mapped_.size() < 2) return;
  // Heads in order of their first frame; each one joins the nearest earlier group (within the
  // radius, in the field plane with merge_in_plane) whose track ended before it began and whose
  // score already reaches min_track_score.
  // Groups are indexed by field x in a multimap so that a long recording's thousands of heads cost
  // O(n log n), not all pairs.
  std::vector<TrackedHead> heads = std::move(mapped_);
  std::stable_sort(heads.begin(), heads.end(), [](const TrackedHead& a, const TrackedHead& b) {
    return a.first_frame < b.first_frame || (a.first_frame == b.first_frame && a.id < b.id);
  });
  const double r = cfg_.merge_radius_m;
  std::vector<TrackedHead> groups;
  std::multimap<double, std::size_t> by_x;
  for (const auto& h : heads) {
    std::size_t best = groups.size();
    double best_d = r;
    auto best_it = by_x.end();
    for (auto it = by_x.lower_bound(h.position.x() - r); it != by_x.end() && it->first <= h.position.x() + r; ++it) {
      const TrackedHead& g = groups[it->second];
      if (g.last_frame >= h.first_frame) continue;  // overlapping in time: two heads
      // Only a head confirmed on its own is found again: fragments that each fall short of the
      // threshold (a leaf misclassified now and then at one place) must not add up to a head.
      if (g.score < cfg_.min_track_score) continue;
      const double d =
          cfg_.merge_in_plane ? (g.position - h.position).head<2>().norm() : (g.position - h.position).norm();
      if (d <= best_d) best_d = d, best = it->second, best_it = it;
    }
    if (best == groups.size()) {
      by_x.emplace(h.position.x(), groups.size());
      groups.push_back(h);
      continue;
    }
    absorb(groups[best], h);
    merged_ids_.push_back({h.id, groups[best].id});
    by_x.erase(best_it);
    by_x.emplace(groups[best].position.x(), best);
  }
  mapped_ = std::move(groups);
}

double TemporalFilter::edge_threshold() const {
  return cfg_.edge_track_score < 0.0 ? cfg_.min_track_score : std::min(cfg_.edge_track_score, cfg_.min_track_score);
}

bool TemporalFilter::passes_edge_rule(const TrackedHead& h) const {
  // A head the recording cut may have been in view for one or two frames only: one detection the
  // classifier is sure of is then evidence enough (edge_single_detection_score), where a track in
  // the middle of the recording would have had frames to repeat it.
  return h.score >= edge_threshold() || h.mean_detection_score >= cfg_.edge_single_detection_score;
}

bool TemporalFilter::confirmed_now(const TrackedHead& h) const {
  // Online the recording's first frame is known, its last is not: only a head seen in the first
  // frame gets the edge rule here.
  return h.first_frame == first_frame_ ? passes_edge_rule(h) : h.score >= cfg_.min_track_score;
}

bool TemporalFilter::confirmed_now(int id) const {
  for (const auto& h : tracked_)
    if (h.id == id) return confirmed_now(h);
  return false;
}

std::vector<TrackedHead> TemporalFilter::finish() {
  if (finished_) throw Error("temporal filter", "finish() called twice");
  finished_ = true;
  for (auto& h : tracked_) mapped_.push_back(h);
  tracked_.clear();
  merge_lost_and_found();
  std::vector<TrackedHead> map;
  // Heads whose track the recording cut (seen in its first or last frame) need edge_track_score,
  // never more than min_track_score (< 0 keeps the paper's single threshold), or one detection
  // scored at least edge_single_detection_score.
  for (const auto& h : mapped_) {
    const bool cut = h.first_frame == first_frame_ || h.last_frame == last_frame_;
    if (cut ? passes_edge_rule(h) : h.score >= cfg_.min_track_score) map.push_back(h);
  }
  if (cfg_.overlap_suppression > 0.0) suppress_overlaps(map);
  std::sort(map.begin(), map.end(), [](const TrackedHead& a, const TrackedHead& b) { return a.id < b.id; });
  return map;
}

void TemporalFilter::suppress_overlaps(std::vector<TrackedHead>& map) const {
  // Strongest first (score, then more frames, then the older track); each head is kept unless a kept
  // one overlaps it. The kept heads are indexed by x, so that a map of a long recording (thousands of
  // heads) is checked against its neighbours only.
  std::sort(map.begin(), map.end(), [](const TrackedHead& a, const TrackedHead& b) {
    if (a.score != b.score) return a.score > b.score;
    if (a.frames_seen != b.frames_seen) return a.frames_seen > b.frames_seen;
    return a.id < b.id;
  });
  double widest_mm = 0.0;
  for (const TrackedHead& h : map) widest_mm = std::max(widest_mm, h.diameter_mm);
  const double reach_m = cfg_.overlap_suppression * widest_mm / 1000.0;  // no limit exceeds it
  std::vector<TrackedHead> kept;
  std::multimap<double, std::size_t> by_x;  // kept heads by field x
  for (const TrackedHead& h : map) {
    bool overlaps = false;
    for (auto it = by_x.lower_bound(h.position.x() - reach_m);
         !overlaps && it != by_x.end() && it->first <= h.position.x() + reach_m; ++it) {
      const TrackedHead& k = kept[it->second];
      const double da = h.diameter_mm > 0.0 ? h.diameter_mm : k.diameter_mm;
      const double db = k.diameter_mm > 0.0 ? k.diameter_mm : h.diameter_mm;
      if (!(da > 0.0)) continue;  // neither size is known
      const double limit_m = cfg_.overlap_suppression * 0.5 * (da + db) / 1000.0;
      overlaps = (h.position - k.position).head<2>().norm() < limit_m;
    }
    if (overlaps) continue;
    by_x.emplace(h.position.x(), kept.size());
    kept.push_back(h);
  }
  map.swap(kept);
}

std::vector<TrackedHead> TemporalFilter::all_heads() const {
  std::vector<TrackedHead> all = mapped_;
  all.insert(all.end(), tracked_.begin(), tracked_.end());
  std::sort(all.begin(), all.end(), [](const TrackedHead& a, const TrackedHead& b) { return a.id < b.id; });
  return all;
}

}  // namespace cropsight::tracking
