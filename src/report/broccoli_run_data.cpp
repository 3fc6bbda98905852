#include "cropsight/report/broccoli_run_data.hpp"

#include <algorithm>
#include <cstdio>
#include <set>

#include "cropsight/core/statistics.hpp"
#include "cropsight/report/broccoli_report_data.hpp"

namespace cropsight::report {

BroccoliRunRecorder::BroccoliRunRecorder(std::vector<int> overlay_frames)
    : overlay_frames_(std::move(overlay_frames)) {}

void BroccoliRunRecorder::add_frame(const RgbdFrame& frame, const pipeline::broccoli::FrameResult& r) {
  const int n = int(detections_per_frame_.size());
  detections_per_frame_.push_back(int(r.detections.size()));
  detections_ += long(r.detections.size());
  camera_path_.emplace_back(r.association.camera_position.x(), r.association.camera_position.y());
  tracking_ms_ += r.track_ms();
  if (std::find(overlay_frames_.begin(), overlay_frames_.end(), n) == overlay_frames_.end()) return;
  pipeline::broccoli::PassMaterial::Overlay o;
  o.frame = n;
  o.depth = frame.depth;
  o.depth_scale = frame.camera.depth_scale;
  std::vector<int> tracks;
  for (const Detection& d : r.detections) {
    o.detections.emplace_back(d.indices, false);  // in the map or not: known after the pass
    tracks.push_back(d.track_id);
  }
  for (const auto& p : r.predicted) o.predicted.push_back(p.indices);
  overlays_.push_back(std::move(o));
  overlay_tracks_.push_back(std::move(tracks));
}

BroccoliReportData BroccoliRunRecorder::finish(const std::vector<tracking::TrackedHead>& map,
                                               std::vector<StageTimer::Stage> stages, const std::string& sequence,
                                               const std::string& model, const std::string& estimator) {
  BroccoliReportData d;
  d.has_truth = false;
  d.sequence = sequence;
  d.model = model;
  d.estimator = estimator;
  d.frames = long(detections_per_frame_.size());
  d.stages = std::move(stages);
  d.tracking_ms = tracking_ms_;
  d.camera_path = camera_path_;
  d.detections_per_frame = detections_per_frame_;
  std::set<int> mapped;
  std::vector<double> sizes;
  for (const auto& h : map) {
    mapped.insert(h.id);
    d.map_heads.push_back({h.position.x(), h.position.y(), h.diameter_mm, true});
    if (h.diameter_mm > 0) sizes.push_back(h.diameter_mm);
  }
  for (std::size_t k = 0; k < overlays_.size(); ++k) {
    for (std::size_t i = 0; i < overlays_[k].detections.size(); ++i)
      overlays_[k].detections[i].second = mapped.count(overlay_tracks_[k][i]) > 0;
    d.overlays.push_back(make_figure(broccoli_overlay(overlays_[k]), "frame " + std::to_string(overlays_[k].frame)));
  }
  char buf[64];
  const auto fixed = [&](double v) { return std::snprintf(buf, sizeof buf, "%.1f", v), std::string(buf); };
  d.metrics = {{"frames", std::to_string(d.frames)},
               {"detections", std::to_string(detections_)},
               {"detections_per_frame", fixed(d.frames ? double(detections_) / double(d.frames) : 0.0)},
               {"map_heads", std::to_string(map.size())},
               {"map_heads_sized", std::to_string(sizes.size())},
               {"median_diameter_mm", sizes.empty() ? std::string("n/a") : fixed(median(sizes))},
               {"harvestable_heads",
                std::to_string(std::count_if(map.begin(), map.end(), [](const auto& h) { return h.harvestable; }))}};
  return d;
}

}  // namespace cropsight::report
