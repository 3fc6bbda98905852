// Trials of the OpenCV trackers on simulated approaches (see visual_tracker_eval.hpp).
#include "cropsight/pipeline/potato/visual_tracker_eval.hpp"

#include <algorithm>

#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/pipeline_timing.hpp"

namespace cropsight::pipeline::potato {
namespace {

const FrameTruth* simulated_target(const std::vector<FrameTruth>& frame) {
  for (const auto& p : frame)
    if (p.target) return &p;
  return nullptr;
}

// A start needs the whole potato in view: a box cut by the border is not what the loop hands over.
bool in_full_view(const FrameTruth& p, const ColorImage& image, int min_pixels) {
  const Detection2D& b = p.box;
  return p.visible_pixels >= min_pixels && b.x1 > 1 && b.y1 > 1 && b.x2 < float(image.width - 1) &&
         b.y2 < float(image.height - 1);
}

}  // namespace

VisualTrackerEvaluation evaluate_visual_tracker(tracking::VisualTrackerKind kind,
                                                const std::vector<TruthSequence>& sequences,
                                                const VisualTrackerTrialConfig& config) {
  const std::string where = "visual tracker evaluation";
  if (kind == tracking::VisualTrackerKind::none) throw Error(where, "tracker 'none' has nothing to evaluate");
  if (config.horizon < 1 || config.stride < 1) throw Error(where, "horizon and stride must be at least 1");
  const OneOpenCvThread one_thread;
  VisualTrackerEvaluation e;
  e.kind = kind;
  double iou_sum = 0, init_sum = 0, update_sum = 0;
  int successes = 0, end_successes = 0, inits = 0;
  for (const auto& seq : sequences) {
    const int n = int(seq.colour.size());
    for (int s = 0; s + 1 < n; s += config.stride) {
      const FrameTruth* start = simulated_target(seq.truth[std::size_t(s)]);
      if (!start || !in_full_view(*start, seq.colour[std::size_t(s)], config.min_visible_pixels)) continue;
      auto tracker = tracking::make_visual_tracker(kind, config.csrt);
      const double c0 = thread_cpu_ms();
      tracker->init(seq.colour[std::size_t(s)], start->box);
      const double init = thread_cpu_ms() - c0;
      if (e.trials == 0) {
        e.first_init_ms = init;
      } else {
        init_sum += init, ++inits;
        e.init_ms_max = std::max(e.init_ms_max, init);
      }
      ++e.trials;
      bool last_ok = false, scored_any = false, lost = false;
      for (int k = 1; k <= config.horizon && s + k < n; ++k) {
        const auto f = std::size_t(s + k);
        std::optional<Detection2D> box;
        if (!lost) {
          const double u0 = thread_cpu_ms();
          box = tracker->update(seq.colour[f]);
          const double u = thread_cpu_ms() - u0;
          update_sum += u;
          e.update_ms_max = std::max(e.update_ms_max, u);
          ++e.update_calls;
          lost = !box;
        }
        const FrameTruth* truth = simulated_target(seq.truth[f]);
        if (!truth || truth->visible_pixels < config.min_visible_pixels) continue;
        const double overlap = box ? double(iou(*box, truth->box)) : 0.0;
        ++e.updates;
        e.gave_up += box ? 0 : 1;
        iou_sum += overlap;
        last_ok = overlap >= config.success_iou;
        successes += last_ok ? 1 : 0;
        scored_any = true;
      }
      end_successes += scored_any && last_ok ? 1 : 0;
    }
  }
  if (e.trials == 0)
    throw Error(where, "no frame with the target potato in full view to start from (" +
                           std::to_string(sequences.size()) + " sequence(s))");
  if (e.updates > 0) {
    e.mean_iou = iou_sum / e.updates;
    e.success_rate = double(successes) / e.updates;
  }
  e.end_success_rate = double(end_successes) / e.trials;
  e.init_ms = inits ? init_sum / inits : e.first_init_ms;
  e.update_ms = e.update_calls ? update_sum / e.update_calls : 0.0;
  return e;
}

}  // namespace cropsight::pipeline::potato
