#include "cropsight/pipeline/broccoli/tracking_eval.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/eval/map_metrics.hpp"
#include "cropsight/pipeline/broccoli/truth.hpp"

namespace cropsight::pipeline::broccoli {

namespace {
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

using Scored = eval::DetectionApAccumulator::Scored;

/// Adds a frame to the all-heads accumulator and to the one with small heads ignored.
void add_both(eval::DetectionApAccumulator& all, eval::DetectionApAccumulator& visible,
              const std::vector<std::vector<int>>& truth, const std::vector<Scored>& dets,
              const std::vector<bool>& small) {
  all.add_frame(truth, dets);
  visible.add_frame(truth, dets, small);
}
}  // namespace

TrackingEvaluator::TrackingEvaluator(TrackingEvalOptions options) : opt_(std::move(options)) {
  if (opt_.map_min_points < 0) throw Error("map_min_points", "must be >= 0 (0: every true head counts)");
}

void TrackingEvaluator::begin_pass(const io::GroundTruth& truth, bool has_poses, const std::string& name) {
  truth_ = &truth;
  has_poses_ = has_poses;
  name_ = name;
  frames_.clear();
  visible_.clear();
  det_truth_.clear();
}

void TrackingEvaluator::add_frame(const RgbdFrame& frame, const Pipeline& pipeline) {
  if (!truth_) throw Error("tracking evaluation", "add_frame before begin_pass");
  if (frame.labels.empty())
    throw Error("frame " + std::to_string(frame.index), "has no label image (ground truth needed)");
  const FrameResult& r = pipeline.last();
  const tracking::HeadMapper& mapper = pipeline.mapper();
  const Detector& detector = pipeline.detector();
  const Config& cfg = pipeline.config();
  estimator_ = cfg.sizing.estimator;
  compute_hull_ = cfg.sizing.compute_hull;
  aligned_cfg_ = cfg.tracking.anchor_first_pose || cfg.tracking.use_poses;
  tracking_ms_ += r.track_ms();
  ++frames_seen_;
  const Eigen::Vector3d& cam = mapper.filter().camera_position();
  if (material_.sequence.empty()) material_.camera_path.emplace_back(cam.x(), cam.y());

  Frame f;
  f.index = frame.index;
  f.predicted = r.predicted;
  // Truth point sets (as the detector evaluation's AP uses them) and the visible heads for the map.
  std::vector<TruthInstance> truth;
  truth_instances(detector.cloud(), cfg.truth.min_truth_points, truth);
  for (const auto& t : truth) {
    f.scored.truth.push_back(t.indices);
    f.small.push_back(t.indices.size() < std::size_t(cfg.truth.visible_truth_points));
    auto& v = visible_[t.id];
    v = std::max(v, int(t.indices.size()));
  }
  // Candidates; a candidate that is a detection is found by its first pixel (segments are disjoint).
  const auto& measured = mapper.detections();
  const std::size_t first = measured.size() - r.detections.size();
  std::map<int, std::size_t> det_by_first;
  for (std::size_t k = 0; k < r.detections.size(); ++k)
    if (!r.detections[k].indices.empty()) det_by_first[r.detections[k].indices.front()] = first + k;
  for (const auto& c : detector.candidates()) {
    f.scored.detections.push_back({c.score, c.segment.indices});
    int di = -1;
    if (c.head && !c.segment.indices.empty()) {
      auto it = det_by_first.find(c.segment.indices.front());
      if (it != det_by_first.end()) di = int(it->second);
    }
    f.cand_det.push_back(di);
    // Per-frame sizes of detections on a true head (the cluster rule of broccoli/truth.hpp).
    const int head =
        di >= 0 ? cluster_truth(c.segment.indices, detector.cloud().labels, cfg.truth.min_head_fraction).head_id : 0;
    if (head > 0) det_truth_[std::size_t(di)] = head;
  }
  // Online: how the robot ranks this frame's detections now.
  std::vector<Scored> online;
  for (std::size_t c = 0; c < f.scored.detections.size(); ++c) {
    const auto& d = f.scored.detections[c];
    const float s =
        f.cand_det[c] >= 0 ? tracking::HeadMapper::online_score(measured[std::size_t(f.cand_det[c])]) : d.score;
    online.push_back({s, std::span<const int>(d.indices)});
  }
  for (const auto& p : f.predicted)
    if (const auto s = tracking::HeadMapper::online_predicted_score(p))
      online.push_back({*s, std::span<const int>(p.indices)});
  add_both(ap_online_, ap_online_visible_, f.scored.truth, online, f.small);

  if (material_.sequence.empty() &&
      std::find(opt_.overlay_frames.begin(), opt_.overlay_frames.end(), frame.index) != opt_.overlay_frames.end() &&
      material_.overlays.size() < opt_.overlay_frames.size()) {
    f.overlay = int(material_.overlays.size());
    PassMaterial::Overlay o;
    o.frame = frame.index;
    o.depth = frame.depth;
    o.depth_scale = frame.camera.depth_scale;
    o.labels = frame.labels;
    for (const auto& d : r.detections) {
      o.detections.emplace_back(d.indices, false);  // whether the head reached the map: end_pass
      f.overlay_tracks.push_back(d.track_id);
    }
    material_.overlays.push_back(std::move(o));
  }
  frames_.push_back(std::move(f));
}

void TrackingEvaluator::end_pass(Pipeline& pipeline) {
  const Stopwatch clock;
  const auto& map = pipeline.finish();
  tracking_ms_ += clock.ms();
  const tracking::HeadMapper& mapper = pipeline.mapper();
  score_frames(mapper);
  add_sizes(mapper);
  add_map(map);
  keep_overlays(mapper);
  if (material_.sequence.empty()) material_.sequence = name_;
  frames_.clear();
  det_truth_.clear();
  truth_ = nullptr;
}

// AP without the filter and offline (the map of the whole pass), and the curves' frames.
void TrackingEvaluator::score_frames(const tracking::HeadMapper& mapper) {
  const auto& measured = mapper.detections();
  for (const auto& f : frames_) {
    std::vector<Scored> single, offline;
    eval::ScoredFrame filtered = f.scored;
    for (std::size_t c = 0; c < f.scored.detections.size(); ++c) {
      const auto& d = f.scored.detections[c];
      single.push_back({d.score, std::span<const int>(d.indices)});
      const float s = f.cand_det[c] >= 0 ? mapper.filtered_score(measured[std::size_t(f.cand_det[c])]) : d.score;
      offline.push_back({s, std::span<const int>(d.indices)});
      filtered.detections[c].score = s;
    }
    // Predicted sets of heads that reached the map rank after the confirmed detections.
    for (const auto& p : f.predicted)
      if (const auto s = mapper.predicted_score(p.track_id)) {
        offline.push_back({*s, std::span<const int>(p.indices)});
        filtered.detections.push_back({*s, p.indices});
      }
    add_both(ap_single_, ap_single_visible_, f.scored.truth, single, f.small);
    add_both(ap_offline_, ap_offline_visible_, f.scored.truth, offline, f.small);
    material_.single_frames.push_back(f.scored);
    material_.offline_frames.push_back(std::move(filtered));
  }
}

// Per-frame sizes (raw estimators and the corrected chosen one) of detections on true heads.
void TrackingEvaluator::add_sizes(const tracking::HeadMapper& mapper) {
  const auto& measured = mapper.detections();
  for (const auto& [di, id] : det_truth_) {
    const auto& m = measured[di];
    const auto* t = truth_->find(id);
    if (!m.size.valid || !t) continue;
    frame_true_.push_back(t->diameter_mm);
    frame_bbox_.push_back(m.size.bbox_mm);
    frame_hull_.push_back(m.size.hull_mm);
    frame_est_.push_back(m.size.diameter_mm);
    if (material_.sequence.empty())
      material_.frame_errors.push_back({std::hypot(double(m.centroid.x()), double(m.centroid.y())),
                                        m.size.bbox_mm - t->diameter_mm, m.size.hull_mm - t->diameter_mm});
  }
}

// The map against the visible true heads (field frame; needs the first pose to share the frame).
void TrackingEvaluator::add_map(const std::vector<tracking::TrackedHead>& map) {
  if (!has_poses_ || !aligned_cfg_) map_unaligned_ = true;
  std::vector<Eigen::Vector3d> est, truth;
  std::vector<Eigen::Vector3d> too_little_seen;  // ignore regions (map_precision_visible)
  std::vector<const io::InstanceTruth*> truth_inst;
  for (const auto& h : map) est.push_back(h.position);
  for (const auto& [id, pts] : visible_) {
    const auto* t = truth_->find(id);
    if (!t) continue;
    if (pts < opt_.map_min_points) {
      too_little_seen.push_back(t->position);
      continue;
    }
    truth.push_back(t->position);
    truth_inst.push_back(t);
  }
  const auto mm = eval::map_metrics(est, truth, {}, too_little_seen);
  map_heads_ += mm.map_heads;
  ignored_ += mm.ignored;
  true_heads_ += mm.true_heads;
  matched_ += mm.matched;
  duplicates_ += mm.duplicates;
  std::vector<char> est_matched(est.size(), 0), truth_matched(truth.size(), 0);
  const bool first_pass = material_.sequence.empty();
  for (const auto& m : mm.matches) {
    est_matched[std::size_t(m.map_index)] = truth_matched[std::size_t(m.truth_index)] = 1;
    match_distance_sum_ += m.distance_m;
    const auto& h = map[std::size_t(m.map_index)];
    if (h.size_samples == 0) continue;
    const double true_mm = truth_inst[std::size_t(m.truth_index)]->diameter_mm;
    head_true_.push_back(true_mm);
    head_est_.push_back(h.diameter_mm);
    head_bbox_.push_back(h.bbox_mm);
    head_hull_.push_back(h.hull_mm);
    if (first_pass) material_.head_sizes.emplace_back(true_mm, h.diameter_mm);
  }
  if (!first_pass) return;
  for (std::size_t i = 0; i < map.size(); ++i)
    material_.map_heads.push_back({map[i].position.x(), map[i].position.y(), map[i].diameter_mm, bool(est_matched[i])});
  for (std::size_t j = 0; j < truth.size(); ++j)
    material_.true_heads.push_back({truth[j].x(), truth[j].y(), truth_inst[j]->diameter_mm, bool(truth_matched[j])});
}

// Overlay frames learn which of their heads reached the map.
void TrackingEvaluator::keep_overlays(const tracking::HeadMapper& mapper) {
  for (const auto& f : frames_) {
    if (f.overlay < 0) continue;
    auto& o = material_.overlays[std::size_t(f.overlay)];
    for (std::size_t k = 0; k < o.detections.size(); ++k)
      o.detections[k].second = mapper.confirmed(f.overlay_tracks[k]);
    for (const auto& p : f.predicted)
      if (mapper.confirmed(p.track_id)) o.predicted.push_back(p.indices);
  }
}

TrackingFigures TrackingEvaluator::figures() const {
  TrackingFigures r;
  r.frames = frames_seen_;
  r.map_aligned = !map_unaligned_;
  r.map_precision = map_unaligned_ || !map_heads_ ? kNan : double(matched_) / map_heads_;
  r.map_precision_visible =
      map_unaligned_ || map_heads_ <= ignored_ ? kNan : double(matched_) / (map_heads_ - ignored_);
  r.map_recall = map_unaligned_ || !true_heads_ ? kNan : double(matched_) / true_heads_;
  r.duplicate_rate = map_unaligned_ || !map_heads_ ? kNan : double(duplicates_) / map_heads_;
  r.count_error = map_heads_ - true_heads_;
  r.count_error_rel = true_heads_ ? double(map_heads_ - true_heads_) / true_heads_ : kNan;
  r.map_heads = map_heads_;
  r.map_true_heads = true_heads_;
  r.map_matched = matched_;
  r.map_ignored = ignored_;
  r.map_mean_distance_m = map_unaligned_ || !matched_ ? kNan : match_distance_sum_ / matched_;
  r.map_min_visible_points = opt_.map_min_points;
  r.size_estimator = estimator_;
  r.hull_computed = compute_hull_;
  r.head_size = eval::size_metrics(head_est_, head_true_);
  r.head_bbox_raw = eval::size_metrics(head_bbox_, head_true_);
  r.head_hull_raw = eval::size_metrics(head_hull_, head_true_);
  r.frame_size = eval::size_metrics(frame_est_, frame_true_);
  r.frame_bbox_raw = eval::size_metrics(frame_bbox_, frame_true_);
  r.frame_hull_raw = eval::size_metrics(frame_hull_, frame_true_);
  r.ap50_single_frame = ap_single_.ap(0.5);
  r.ap50_online = ap_online_.ap(0.5);
  r.ap50_offline = ap_offline_.ap(0.5);
  r.map50_95_single_frame = ap_single_.map50_95();
  r.map50_95_online = ap_online_.map50_95();
  r.map50_95_offline = ap_offline_.map50_95();
  r.ap50_single_frame_visible = ap_single_visible_.ap(0.5);
  r.ap50_online_visible = ap_online_visible_.ap(0.5);
  r.ap50_offline_visible = ap_offline_visible_.ap(0.5);
  r.tracking_ms_per_frame = frames_seen_ ? tracking_ms_ / double(frames_seen_) : 0.0;
  if (opt_.fit_size_bias) {
    r.bbox_fit = measure::fit_size_bias(frame_bbox_, frame_true_, "--fit-size-bias (bbox)");
    if (compute_hull_) r.hull_fit = measure::fit_size_bias(frame_hull_, frame_true_, "--fit-size-bias (hull)");
    // The map-level fit needs spread in the mapped heads' true sizes; a pass too short to give it
    // still has the per-detection fit.
    try {
      r.head_bbox_fit = measure::fit_size_bias(head_bbox_, head_true_, "--fit-size-bias (bbox, mapped heads)");
      if (compute_hull_)
        r.head_hull_fit = measure::fit_size_bias(head_hull_, head_true_, "--fit-size-bias (hull, mapped heads)");
    } catch (const Error&) {
      r.head_bbox_fit.reset();
      r.head_hull_fit.reset();
    }
  }
  return r;
}

}  // namespace cropsight::pipeline::broccoli
