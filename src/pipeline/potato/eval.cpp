// Harvest-run evaluation against simulated truth (see potato/eval.hpp).
#include "cropsight/pipeline/potato/eval.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"

namespace cropsight::pipeline::potato {

double axis_angle_error(double a, double b) {
  double d = std::fmod(std::abs(a - b), M_PI);
  return std::min(d, M_PI - d);
}

namespace {
AxisError summarise(const std::vector<double>& e) {
  AxisError a;
  if (e.empty()) return a;
  for (double v : e) a.mean_mm += v, a.mae_mm += std::abs(v);
  a.mean_mm /= double(e.size());
  a.mae_mm /= double(e.size());
  for (double v : e) a.std_mm += (v - a.mean_mm) * (v - a.mean_mm);
  a.std_mm = std::sqrt(a.std_mm / double(e.size()));
  return a;
}
}  // namespace

void Evaluator::add(const FrameResult& result, const std::vector<FrameTruth>& truth) {
  Figures& ev = figures_;
  const HarvestTarget& r = result.target;
  FrameScore& row = ev.per_frame.emplace_back();
  row.frame = ev.frames++;
  if (r.state == tracking::TargetState::lost) ++ev.lost_events;
  if (!r.detection) return;
  ++ev.frames_with_target;
  const FrameTruth* best = nullptr;
  float best_iou = float(min_iou_);
  for (const auto& t : truth) {
    if (t.visible_pixels == 0) continue;
    const float o = iou(r.box, t.box);
    if (o >= best_iou) best_iou = o, best = &t;
  }
  if (!best) return;
  row.potato = best->id;
  row.on_target = best->target;
  row.iou = best_iou;
  row.true_z_m = best->centre_camera.z();
  ++ev.frames_matched;
  if (best->target) ++ev.frames_on_target;
  auto [it, fresh] = potato_of_target_.emplace(r.target_id, best->id);
  if (fresh) ++ev.targets;
  if (!fresh && it->second != best->id) {
    ++ev.target_switches;
    it->second = best->id;
  }
  if (r.depth_ok) {
    row.positioned = true;
    row.cut = r.cut;
    row.error_mm = 1000.0 * (Eigen::Vector3d(r.x, r.y, r.z) - best->centre_camera);
  }
  if (r.depth_ok && r.cut) {
    ++ev.frames_cut;
    errors_.cx.push_back(row.error_mm.x());
    errors_.cy.push_back(row.error_mm.y());
    errors_.cz.push_back(row.error_mm.z());
  } else if (r.depth_ok) {
    ++ev.frames_positioned;
    errors_.ex.push_back(row.error_mm.x());
    errors_.ey.push_back(row.error_mm.y());
    errors_.ez.push_back(row.error_mm.z());
    errors_.el.push_back(1000.0 * (std::max(r.width, r.height) - best->length_m));
    errors_.ew.push_back(1000.0 * (std::min(r.width, r.height) - best->width_m));
  }
  if (r.angle_ok) {
    row.angle_error_deg = axis_angle_error(r.angle, best->angle_rad) * 180.0 / M_PI;
    errors_.ea.push_back(row.angle_error_deg);
    if (!r.cut) errors_.ea_full.push_back(row.angle_error_deg);
  }
}

Figures Evaluator::figures() const {
  Figures ev = figures_;
  ev.x = summarise(errors_.ex);
  ev.y = summarise(errors_.ey);
  ev.z = summarise(errors_.ez);
  ev.cut_x = summarise(errors_.cx);
  ev.cut_y = summarise(errors_.cy);
  ev.cut_z = summarise(errors_.cz);
  ev.length_mae_mm = summarise(errors_.el).mae_mm;
  ev.width_mae_mm = summarise(errors_.ew).mae_mm;
  ev.angle_mae_deg = summarise(errors_.ea).mae_mm;
  ev.angles = int(errors_.ea.size());
  ev.angle_mae_full_view_deg = summarise(errors_.ea_full).mae_mm;
  ev.angles_full_view = int(errors_.ea_full.size());
  return ev;
}

Figures evaluate_potato_run(const std::vector<FrameResult>& run, const std::vector<std::vector<FrameTruth>>& truth,
                            double min_iou) {
  if (run.size() != truth.size()) throw Error("potato evaluation", "run and truth have different frame counts");
  Evaluator ev(min_iou);
  for (std::size_t f = 0; f < run.size(); ++f) ev.add(run[f], truth[f]);
  return ev.figures();
}

StageTimes stage_times(const std::vector<FrameResult>& run) {
  StageTimes t;
  if (run.empty()) return t;
  for (const auto& r : run) {
    t.detect += r.timer.ms("detect"), t.locate += r.timer.ms("locate"), t.track += r.timer.ms("track");
    t.orient += r.timer.ms("orient");
    t.max_total = std::max(t.max_total, r.timer.total_ms());
  }
  const double n = double(run.size());
  t.detect /= n, t.locate /= n, t.track /= n, t.orient /= n;
  t.total = t.detect + t.locate + t.track + t.orient;
  return t;
}

SequenceEvaluation evaluate_potato_sequence(Pipeline& pipeline, const std::filesystem::path& seq, double min_iou) {
  const io::SequenceReader reader(seq);
  require_truth(reader, seq);
  SequenceEvaluation out;
  pipeline.reset();
  for (int i = 0; i < reader.size(); ++i) {
    const RgbdFrame f = reader.read(i);
    out.truth.push_back(frame_truth(reader, f, seq));
    out.run.push_back(pipeline.process(f));
  }
  out.figures = evaluate_potato_run(out.run, out.truth, min_iou);
  out.ms = stage_times(out.run);
  return out;
}

}  // namespace cropsight::pipeline::potato
