// Harvest-run evaluation against simulated truth (see potato_eval.hpp).
#include "cropsight/pipeline/potato/potato_eval.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "cropsight/core/error.hpp"

namespace cropsight::pipeline {

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

PotatoEvaluation evaluate_potato_run(const std::vector<PotatoFrameResult>& run,
                                     const std::vector<std::vector<sim::PotatoFrameTruth>>& truth, double min_iou) {
  if (run.size() != truth.size()) throw Error("potato evaluation", "run and truth have different frame counts");
  PotatoEvaluation ev;
  ev.frames = int(run.size());
  std::vector<double> ex, ey, ez, el, ew, ea;
  std::map<int, int> potato_of_target;  // target id -> matched potato id
  for (std::size_t f = 0; f < run.size(); ++f) {
    const auto& r = run[f];
    if (r.state == tracking::TargetState::lost) ++ev.lost_events;
    if (!r.box) continue;
    ++ev.frames_with_target;
    const sim::PotatoFrameTruth* best = nullptr;
    float best_iou = float(min_iou);
    for (const auto& t : truth[f]) {
      if (t.visible_pixels == 0) continue;
      const float o = iou(*r.box, t.box);
      if (o >= best_iou) best_iou = o, best = &t;
    }
    if (!best) continue;
    ++ev.frames_matched;
    auto [it, fresh] = potato_of_target.emplace(r.target_id, best->id);
    if (fresh) ++ev.targets;
    if (!fresh && it->second != best->id) {
      ++ev.target_switches;
      it->second = best->id;
    }
    if (r.depth_ok) {
      ++ev.frames_positioned;
      ex.push_back(1000.0 * (r.xyz.x() - best->centre_camera.x()));
      ey.push_back(1000.0 * (r.xyz.y() - best->centre_camera.y()));
      ez.push_back(1000.0 * (r.xyz.z() - best->centre_camera.z()));
      el.push_back(1000.0 * (std::max(r.width_m, r.height_m) - best->length_m));
      ew.push_back(1000.0 * (std::min(r.width_m, r.height_m) - best->width_m));
    }
    if (r.angle_rad) ea.push_back(axis_angle_error(*r.angle_rad, best->angle_rad) * 180.0 / M_PI);
  }
  ev.x = summarise(ex);
  ev.y = summarise(ey);
  ev.z = summarise(ez);
  ev.length_mae_mm = summarise(el).mae_mm;
  ev.width_mae_mm = summarise(ew).mae_mm;
  ev.angle_mae_deg = summarise(ea).mae_mm;
  ev.angles = int(ea.size());
  return ev;
}

}  // namespace cropsight::pipeline
