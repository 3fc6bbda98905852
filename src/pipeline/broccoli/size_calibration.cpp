#include "cropsight/pipeline/broccoli/size_calibration.hpp"

#include <map>

#include "cropsight/core/error.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/tracking_eval.hpp"

namespace cropsight::pipeline::broccoli {

SizeCorrection fit_size_correction(std::shared_ptr<const learning::Model> model, Config cfg,
                                   const std::vector<std::string>& sequences,
                                   const std::function<void(const std::string&, int, int)>& progress) {
  cfg.track = true;
  cfg.sizing.hull_scale = cfg.sizing.bbox_scale = 1.0;
  cfg.sizing.hull_offset_mm = cfg.sizing.bbox_offset_mm = 0.0;
  Pipeline pipe(cfg, std::move(model));
  std::map<std::string, TrackingEvaluator> by_variety;
  for (const std::string& dir : sequences) {
    const io::SequenceReader reader(dir);
    if (!reader.info().has_labels) throw Error(dir, "sequence has no labels/ (the size fit needs ground truth)");
    if (!reader.info().has_groundtruth) throw Error(dir, "sequence has no groundtruth.json (the true head sizes)");
    const auto& attributes = reader.groundtruth().attributes;
    const auto variety = attributes.find("variety");
    TrackingEvaluator& tracker =
        by_variety
            .try_emplace(variety == attributes.end() ? "" : variety->second, TrackingEvalOptions{.fit_size_bias = true})
            .first->second;
    pipe.reset();
    tracker.begin_pass(reader.groundtruth(), !reader.poses().empty(), dir);
    for (int i = 0; i < reader.size(); ++i) {
      const RgbdFrame frame = reader.read(i);
      pipe.process(frame);
      tracker.add_frame(frame, pipe);
      if (progress) progress(dir, i + 1, reader.size());
    }
    tracker.end_pass(pipe);
  }
  SizeCorrection out{{0.0, 0.0, 0, 0.0, 0.0}, {0.0, 0.0, 0, 0.0, 0.0}, cfg.sizing.hull_max_points, {}};
  const auto add = [k = 1.0 / double(by_variety.size())](measure::BiasFit& sum, const measure::BiasFit& f) {
    sum.scale += k * f.scale;
    sum.offset_mm += k * f.offset_mm;
    sum.n += f.n;
    sum.rms_before_mm += k * f.rms_before_mm;
    sum.rms_after_mm += k * f.rms_after_mm;
  };
  for (auto& [variety, tracker] : by_variety) {
    TrackingFigures f;
    try {
      f = tracker.figures();
    } catch (const Error& e) {
      throw Error("size calibration", "variety '" + variety + "': " + e.what());
    }
    if (!f.hull_fit || !f.bbox_fit) throw Error("size calibration", "variety '" + variety + "': no size was fitted");
    add(out.hull, *f.hull_fit);
    add(out.bbox, *f.bbox_fit);
    out.groups.push_back(variety);
  }
  if (out.groups.empty()) throw Error("size calibration", "no labelled pass to fit");
  return out;
}

ConfigMap size_correction_values(const SizeCorrection& fit) {
  return {{"sizing.hull_scale", detail::exact_number(fit.hull.scale)},
          {"sizing.hull_offset_mm", detail::exact_number(fit.hull.offset_mm)},
          {"sizing.bbox_scale", detail::exact_number(fit.bbox.scale)},
          {"sizing.bbox_offset_mm", detail::exact_number(fit.bbox.offset_mm)},
          {"sizing.hull_max_points", std::to_string(fit.hull_max_points)}};
}

}  // namespace cropsight::pipeline::broccoli
