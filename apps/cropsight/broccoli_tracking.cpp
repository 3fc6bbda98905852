#include "broccoli_tracking.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <span>

#include "broccoli_cli.hpp"
#include "cli_common.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/eval/detection_ap.hpp"
#include "cropsight/eval/map_metrics.hpp"
#include "cropsight/eval/size_metrics.hpp"
#include "cropsight/pipeline/broccoli_truth.hpp"
#include "cropsight/report/render.hpp"
#include "cropsight/report/sequence_page.hpp"
#include "cropsight/tracking/field_map_io.hpp"

namespace cropsight::cli {

namespace {
nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

tracking::HeadMapperConfig mapper_config(const ConfigMap& keys, const std::string& where) {
  tracking::HeadMapperConfig cfg;
  cfg.apply(keys, where);
  return cfg;
}

nlohmann::json size_json(const eval::SizeMetrics& m) {
  return {{"n", m.n},
          {"mede_mm", num(m.mede_mm)},
          {"mad_mm", num(m.mad_mm)},
          {"medae_mm", num(m.medae_mm)},
          {"pearson_r", num(m.pearson_r)},
          {"rmse_mm", num(m.rmse_mm)}};
}
}  // namespace

void add_track_options(CLI::App* cmd, TrackOptions& o, bool detect) {
  cmd->add_flag("--track", o.track,
                "Size every detection and run the temporal filter (keys sizing.*, tracking.* of the preset)");
  if (detect) {
    cmd->add_option("--map", o.map, "With --track: write the field map CSV (id, x, y, z, diameters, frames, ...)");
  } else {
    cmd->add_option("--map-min-points", o.map_min_points,
                    "With --track: a true head counts for map recall when a frame shows it with at least this "
                    "many valid points (default 300)");
    cmd->add_flag("--fit-size-bias", o.fit_size_bias,
                  "With --track: fit the size bias correction (scale, offset) of both estimators on these "
                  "sequences (use training data) and print the sizing.* values");
  }
}

ConfigMap take_tracking_keys(ConfigMap& all) {
  ConfigMap mine;
  for (auto it = all.begin(); it != all.end();) {
    if (it->first.rfind("sizing.", 0) == 0 || it->first.rfind("tracking.", 0) == 0) {
      mine.insert(*it);
      it = all.erase(it);
    } else {
      ++it;
    }
  }
  return mine;
}

void print_tracking_summary(const nlohmann::json& j) {
  auto f = [&](const char* k) { return j.contains(k) && j[k].is_number() ? j[k].get<double>() : NAN; };
  std::printf("  map: precision %.3f  recall %.3f  duplicates %.3f  count error %+.0f (%g heads mapped, %g true)\n",
              f("map_precision"), f("map_recall"), f("duplicate_rate"), f("count_error"), f("map_heads"),
              f("map_true_heads"));
  std::printf("  size (%s, per head): MEDE %.1f mm  MAD %.1f mm  r %.3f  (%g heads)\n",
              j.value("size_estimator", std::string("?")).c_str(), f("size_mede_mm"), f("size_mad_mm"),
              f("size_pearson_r"), f("size_heads"));
  std::printf("  size per frame: MEDE %.1f mm  MAD %.1f mm  r %.3f\n", f("size_frame_mede_mm"), f("size_frame_mad_mm"),
              f("size_frame_pearson_r"));
  std::printf("  AP50 single frame %.4f  with temporal filter %.4f; sizing + tracking %.3f ms/frame\n",
              f("ap50_single_frame"), f("ap50_temporal"), f("tracking_ms_per_frame"));
  if (j.contains("size_bias_fit"))
    for (const char* e : {"bbox", "hull"})
      if (j["size_bias_fit"].contains(e))
        std::printf("  size bias fit (%s): --set %s  (RMS %.1f → %.1f mm)\n", e,
                    j["size_bias_fit"][e]["set"].get<std::string>().c_str(),
                    j["size_bias_fit"][e]["rms_before_mm"].get<double>(),
                    j["size_bias_fit"][e]["rms_after_mm"].get<double>());
}

// ---------------------------------------------------------------------------------------------
// detect broccoli --track

DetectTracking::DetectTracking(const TrackOptions& o, const ConfigMap& keys, const std::string& where)
    : o_(o), mapper_(mapper_config(keys, where)) {
  if (!o_.map.empty() && !o_.track) throw Error("--map", "needs --track");
}

void DetectTracking::frame(const RgbdFrame& frame, const pipeline::BroccoliDetector& detector,
                           std::vector<Detection>& dets, nlohmann::json& line) {
  const auto a = mapper_.add_frame(frame.index, detector.cloud(), dets, frame.camera_position);
  nlohmann::json heads = nlohmann::json::array();
  const auto& measured = mapper_.detections();
  const std::size_t first = measured.size() - dets.size();
  for (std::size_t k = 0; k < dets.size(); ++k) {
    const auto& m = measured[first + k];
    heads.push_back({{"id", int(k) + 1},
                     {"track_id", m.track_id},
                     {"diameter_mm", m.size.valid ? num(m.size.diameter_mm) : nlohmann::json(nullptr)},
                     {"bbox_mm", m.size.valid ? num(m.size.bbox_mm) : nlohmann::json(nullptr)},
                     {"hull_mm", m.size.valid ? num(m.size.hull_mm) : nlohmann::json(nullptr)},
                     {"harvestable", m.size.harvestable},
                     {"field", {m.field_position.x(), m.field_position.y(), m.field_position.z()}}});
  }
  line["heads"] = std::move(heads);
  // Heads of T this frame missed (tracking.predict_missed): where the filter expects them. Their
  // tracks may still fail to reach the map; compare track_id with --map.
  nlohmann::json predicted = nlohmann::json::array();
  for (const auto& p : mapper_.predict_missed(detector.cloud(), frame.camera))
    predicted.push_back({{"track_id", p.track_id},
                         {"points", p.indices.size()},
                         {"centroid", {p.centroid.x(), p.centroid.y(), p.centroid.z()}}});
  line["predicted"] = std::move(predicted);
  line["camera_estimate"] = {a.camera_position.x(), a.camera_position.y(), a.camera_position.z()};
}

void DetectTracking::finish(nlohmann::json& summary) {
  const auto& map = mapper_.finish();
  int harvestable = 0;
  for (const auto& h : map) harvestable += h.harvestable;
  summary["map_heads"] = map.size();
  summary["harvestable"] = harvestable;
  summary["size_estimator"] = mapper_.sizer().config().estimator;
  if (!o_.map.empty()) {
    tracking::write_field_map(o_.map, map);
    summary["map"] = o_.map;
  }
}

// ---------------------------------------------------------------------------------------------
// eval broccoli --track, report --model

EvalTracking::EvalTracking(const ConfigMap& keys, const pipeline::BroccoliDetectorConfig& detector_cfg,
                           const std::string& where, std::vector<int> overlay_frames)
    : keys_(keys),
      where_(where),
      cfg_(mapper_config(keys, where)),
      det_cfg_(detector_cfg),
      overlay_frames_(std::move(overlay_frames)) {
  data_.estimator = cfg_.sizing.estimator;
}

void EvalTracking::begin_sequence(const io::SequenceReader& reader) {
  mapper_.emplace(cfg_);
  reader_ = &reader;
  sequence_ = reader.info().dir.string();
  frames_.clear();
  visible_.clear();
}

void EvalTracking::frame(const RgbdFrame& frame, const pipeline::BroccoliDetector& detector) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Detection> dets = detector.detections();
  const std::size_t first = mapper_->detections().size();
  mapper_->add_frame(frame.index, detector.cloud(), dets, frame.camera_position);
  std::vector<tracking::PredictedHead> predicted = mapper_->predict_missed(detector.cloud(), frame.camera);
  tracking_ms_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  data_.camera_path.emplace_back(mapper_->filter().camera_position().x(), mapper_->filter().camera_position().y());

  Frame f;
  f.index = frame.index;
  f.predicted = std::move(predicted);
  // Truth point sets (as the evaluator's AP uses them) and the visible heads for the map.
  std::vector<pipeline::TruthInstance> truth;
  pipeline::truth_instances(detector.cloud(), det_cfg_.detection.min_truth_points, truth);
  for (const auto& t : truth) {
    f.pr.truth.push_back(t.indices);
    auto& v = visible_[t.id];
    v = std::max(v, int(t.indices.size()));
  }
  // Candidates; a candidate that is a detection is found by its first pixel (segments are disjoint).
  std::map<int, std::size_t> det_by_first;
  for (std::size_t k = 0; k < dets.size(); ++k)
    if (!dets[k].indices.empty()) det_by_first[dets[k].indices.front()] = first + k;
  for (const auto& c : detector.candidates()) {
    f.pr.detections.push_back({c.score, c.segment.indices});
    int di = -1;
    if (c.head && !c.segment.indices.empty()) {
      auto it = det_by_first.find(c.segment.indices.front());
      if (it != det_by_first.end()) di = int(it->second);
    }
    f.cand_det.push_back(di);
    // Per-frame sizes of detections on a true head.
    if (di >= 0 && c.truth.head_id > 0) det_truth_[std::size_t(di)] = c.truth.head_id;
  }
  if (std::find(overlay_frames_.begin(), overlay_frames_.end(), frame.index) != overlay_frames_.end() &&
      data_.overlays.size() + overlay_pending_ < overlay_frames_.size()) {
    f.overlay = true;
    ++overlay_pending_;
    f.image = report::depth_colormap(frame.depth, frame.camera.depth_scale);
    f.labels = frame.labels;
    for (const auto& d : dets) f.det_pixels.emplace_back(d.indices, d.track_id);
  }
  ++frames_seen_;
  frames_.push_back(std::move(f));
}

void EvalTracking::end_sequence() {
  const auto t0 = std::chrono::steady_clock::now();
  const auto& map = mapper_->finish();
  tracking_ms_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const auto& measured = mapper_->detections();
  const auto& gt = reader_->groundtruth();
  std::map<int, const io::InstanceTruth*> truth_by_id;
  for (const auto& t : gt.instances) truth_by_id[t.id] = &t;

  // AP with and without the filter, and the curves.
  for (const auto& f : frames_) {
    std::vector<eval::DetectionApAccumulator::Scored> single, tracked;
    report::PrFrame filtered = f.pr;
    for (std::size_t c = 0; c < f.pr.detections.size(); ++c) {
      const auto& d = f.pr.detections[c];
      single.push_back({d.score, std::span<const int>(d.indices)});
      const float s = f.cand_det[c] >= 0 ? mapper_->filtered_score(measured[std::size_t(f.cand_det[c])]) : d.score;
      tracked.push_back({s, std::span<const int>(d.indices)});
      filtered.detections[c].score = s;
    }
    // Predicted sets of heads that reached the map rank after the confirmed detections.
    for (const auto& p : f.predicted)
      if (const auto s = mapper_->predicted_score(p.track_id)) {
        tracked.push_back({*s, std::span<const int>(p.indices)});
        filtered.detections.push_back({*s, p.indices});
      }
    ap_single_.add_frame(f.pr.truth, single);
    ap_tracked_.add_frame(f.pr.truth, tracked);
    pr_single_.push_back(f.pr);
    pr_tracked_.push_back(std::move(filtered));
  }

  // Per-frame sizes (raw estimators and the corrected chosen one) of detections on true heads.
  for (const auto& [di, id] : det_truth_) {
    const auto& m = measured[di];
    auto it = truth_by_id.find(id);
    if (!m.size.valid || it == truth_by_id.end()) continue;
    const double truth_mm = it->second->diameter_mm;
    frame_true_.push_back(truth_mm);
    frame_bbox_.push_back(m.size.bbox_mm);
    frame_hull_.push_back(m.size.hull_mm);
    frame_est_.push_back(m.size.diameter_mm);
    if (data_.overlays.empty() || data_.sequence == sequence_)
      data_.frame_errors.push_back({std::hypot(double(m.centroid.x()), double(m.centroid.y())),
                                    m.size.bbox_mm - truth_mm, m.size.hull_mm - truth_mm});
  }

  // The map against the visible true heads (field frame; needs the first pose to share the frame).
  const bool aligned = !reader_->poses().empty() && (cfg_.tracking.anchor_first_pose || cfg_.tracking.use_poses);
  if (!aligned) map_unaligned_ = true;
  std::vector<Eigen::Vector3d> est, truth;
  std::vector<const io::InstanceTruth*> truth_inst;
  for (const auto& h : map) est.push_back(h.position);
  for (const auto& [id, pts] : visible_) {
    auto it = truth_by_id.find(id);
    if (it == truth_by_id.end() || pts < map_min_points_) continue;
    truth.push_back(it->second->position);
    truth_inst.push_back(it->second);
  }
  const auto mm = eval::map_metrics(est, truth);
  map_heads_ += mm.map_heads;
  true_heads_ += mm.true_heads;
  matched_ += mm.matched;
  duplicates_ += mm.duplicates;
  std::vector<char> est_matched(est.size(), 0), truth_matched(truth.size(), 0);
  for (const auto& m : mm.matches) {
    est_matched[std::size_t(m.map_index)] = truth_matched[std::size_t(m.truth_index)] = 1;
    const auto& h = map[std::size_t(m.map_index)];
    if (h.size_samples == 0) continue;
    head_true_.push_back(truth_inst[std::size_t(m.truth_index)]->diameter_mm);
    head_est_.push_back(h.diameter_mm);
    head_bbox_.push_back(h.bbox_mm);
    head_hull_.push_back(h.hull_mm);
  }

  // Report data: the first sequence's map and overlays.
  if (data_.sequence.empty()) {
    data_.sequence = sequence_;
    for (std::size_t i = 0; i < map.size(); ++i)
      data_.map_heads.push_back({map[i].position.x(), map[i].position.y(), map[i].diameter_mm, bool(est_matched[i])});
    for (std::size_t j = 0; j < truth.size(); ++j)
      data_.true_heads.push_back({truth[j].x(), truth[j].y(), truth_inst[j]->diameter_mm, bool(truth_matched[j])});
    for (const auto& m : mm.matches) {
      const auto& h = map[std::size_t(m.map_index)];
      if (h.size_samples > 0)
        data_.head_sizes.push_back({truth_inst[std::size_t(m.truth_index)]->diameter_mm, h.diameter_mm});
    }
    for (auto& f : frames_) {
      if (!f.overlay) continue;
      ColorImage img = f.image;
      for (const auto& [pixels, track] : f.det_pixels) {
        const bool ok = mapper_->confirmed(track);
        for (int i : pixels) {
          auto& p = img.data[std::size_t(i)];
          p = ok ? Rgb8{uint8_t(p.r / 3), uint8_t(110 + p.g / 2), uint8_t(p.b / 3)}
                 : Rgb8{uint8_t(120 + p.r / 2), uint8_t(p.g / 3), uint8_t(p.b / 3)};
        }
      }
      for (const auto& head : f.predicted) {
        if (!mapper_->confirmed(head.track_id)) continue;
        for (int i : head.indices) {
          auto& p = img.data[std::size_t(i)];
          p = Rgb8{uint8_t(200 + p.r / 5), uint8_t(p.g / 4),
                   uint8_t(200 + p.b / 5)};  // magenta: not in the depth colours
        }
      }
      if (!f.labels.data.empty()) report::draw_label_outlines(img, f.labels);
      data_.overlays.push_back(report::make_figure(report::upscale(img, 1), "frame " + std::to_string(f.index)));
    }
  }
  frames_.clear();
  det_truth_.clear();
  overlay_pending_ = 0;
  mapper_.reset();
}

nlohmann::json EvalTracking::json(bool fit_size_bias) {
  nlohmann::json j;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (map_unaligned_) {
    j["map_note"] = "a sequence has no poses.csv: the map cannot be placed in the truth's field frame";
  }
  j["map_precision"] = num(map_unaligned_ || !map_heads_ ? nan : double(matched_) / map_heads_);
  j["map_recall"] = num(map_unaligned_ || !true_heads_ ? nan : double(matched_) / true_heads_);
  j["duplicate_rate"] = num(map_unaligned_ || !map_heads_ ? nan : double(duplicates_) / map_heads_);
  j["count_error"] = map_heads_ - true_heads_;
  j["count_error_rel"] = num(true_heads_ ? double(map_heads_ - true_heads_) / true_heads_ : nan);
  j["map_heads"] = map_heads_;
  j["map_true_heads"] = true_heads_;
  j["map_matched"] = matched_;
  j["map_min_visible_points"] = map_min_points_;
  const auto head = eval::size_metrics(head_est_, head_true_);
  j["size_estimator"] = cfg_.sizing.estimator;
  j["size_mede_mm"] = num(head.mede_mm);
  j["size_mad_mm"] = num(head.mad_mm);
  j["size_pearson_r"] = num(head.pearson_r);
  j["size_heads"] = head.n;
  j["size_per_head"] = {{"chosen", size_json(head)},
                        {"bbox_raw", size_json(eval::size_metrics(head_bbox_, head_true_))},
                        {"hull_raw", cfg_.sizing.compute_hull ? size_json(eval::size_metrics(head_hull_, head_true_))
                                                              : nlohmann::json(nullptr)}};
  const auto fr = eval::size_metrics(frame_est_, frame_true_);
  j["size_frame_mede_mm"] = num(fr.mede_mm);
  j["size_frame_mad_mm"] = num(fr.mad_mm);
  j["size_frame_pearson_r"] = num(fr.pearson_r);
  j["size_per_frame"] = {{"chosen", size_json(fr)},
                         {"bbox_raw", size_json(eval::size_metrics(frame_bbox_, frame_true_))},
                         {"hull_raw", cfg_.sizing.compute_hull ? size_json(eval::size_metrics(frame_hull_, frame_true_))
                                                               : nlohmann::json(nullptr)}};
  j["ap50_single_frame"] = num(ap_single_.ap(0.5));
  j["ap50_temporal"] = num(ap_tracked_.ap(0.5));
  j["map50_95_single_frame"] = num(ap_single_.map50_95());
  j["map50_95_temporal"] = num(ap_tracked_.map50_95());
  j["tracking_ms_per_frame"] = frames_seen_ ? tracking_ms_ / double(frames_seen_) : 0.0;
  if (fit_size_bias) {
    nlohmann::json fit;
    for (const auto& [name, est] : {std::pair<std::string, const std::vector<double>*>{"bbox", &frame_bbox_},
                                    std::pair<std::string, const std::vector<double>*>{"hull", &frame_hull_}}) {
      if (name == "hull" && !cfg_.sizing.compute_hull) continue;
      const auto f = measure::fit_size_bias(*est, frame_true_, "--fit-size-bias (" + name + ")");
      fit[name] = {{"scale", f.scale},
                   {"offset_mm", f.offset_mm},
                   {"n", f.n},
                   {"rms_before_mm", f.rms_before_mm},
                   {"rms_after_mm", f.rms_after_mm},
                   {"set", "sizing." + name + "_scale=" + std::to_string(f.scale) + " sizing." + name +
                               "_offset_mm=" + std::to_string(f.offset_mm)}};
    }
    j["size_bias_fit"] = fit;
  }

  // Report figures.
  data_.frames = frames_seen_;
  data_.tracking_ms = tracking_ms_;
  data_.pr_single = report::pr_curves(pr_single_, report::coco_thresholds());
  data_.pr_tracked = report::pr_curves(pr_tracked_, report::coco_thresholds());
  auto fmt = [](const nlohmann::json& v) {
    if (v.is_null()) return std::string("n/a");
    char b[64];
    std::snprintf(b, sizeof b, v.is_number_integer() ? "%.0f" : "%.3f", v.get<double>());
    return std::string(b);
  };
  data_.metrics.clear();
  for (const char* k : {"map_precision", "map_recall", "duplicate_rate", "count_error", "map_heads", "map_true_heads",
                        "size_mede_mm", "size_mad_mm", "size_pearson_r", "size_heads", "ap50_single_frame",
                        "ap50_temporal", "map50_95_single_frame", "map50_95_temporal", "tracking_ms_per_frame"})
    data_.metrics.emplace_back(k, fmt(j[k]));
  return j;
}

// ---------------------------------------------------------------------------------------------
// report --model

nlohmann::json add_broccoli_report(report::HtmlPage& page, const std::string& data, const std::string& model_path,
                                   ConfigMap config, int frames_shown, bool quiet) {
  const auto model = load_broccoli_model(model_path);
  const ConfigMap track_keys = take_tracking_keys(config);
  const auto cfg = pipeline::config_for_model(*model, config, model_path);
  pipeline::BroccoliDetector detector(cfg);
  detector.set_model(model, model_path);
  io::SequenceReader reader(data);
  if (!reader.info().has_labels) throw Error(data, "sequence has no labels/ (the broccoli report needs ground truth)");
  EvalTracking tracker(track_keys, cfg, "--set", report::evenly_spaced_frames(reader.size(), frames_shown));
  tracker.begin_sequence(reader);
  Progress progress("report broccoli: " + data, reader.size(), quiet);
  for (int i = 0; i < reader.size(); ++i) {
    const RgbdFrame frame = reader.read(i);
    detector.process(frame);
    tracker.frame(frame, detector);
    progress.update(i + 1);
  }
  progress.finish();
  tracker.end_sequence();
  nlohmann::json j = tracker.json(false);
  auto& d = tracker.report_data();
  d.model = model_path;
  d.stages = detector.timer().stages();
  report::add_broccoli_sections(page, d);
  return j;
}

}  // namespace cropsight::cli
