#pragma once
// The size correction of a broccoli model (Kusumam §4.4's sizes, bias-corrected): a model's head
// segments are a few millimetres smaller than the heads (the rim falls off the depth edge), by an
// amount that depends on the model and on sizing.hull_max_points. The correction is fitted on the
// model's own labelled training passes (a calibration, not a result: judge it on other passes)
// and recorded in the model file's config block, so every command that loads the model sizes with
// it and no constant has to be copied by hand.
//
// Each variety weighs the same: the passes are grouped by their groundtruth.json attribute
// "variety" (one group when none says), each group gets its own fit, and the correction is the
// mean of the groups' scales and offsets. One pooled fit would follow whichever variety has the
// most detections: for the general model, 16 randomised passes outweigh the four uk and spain ones,
// and on validation passes (uk, spain, random, random-wide: docs/experiments/2026-12-07-broccoli-
// size-correction-in-the-model.md) the pooled fit left a median error of -3.4 mm, the balanced
// one -1.9 mm.
#include <functional>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/measure/head_size.hpp"
#include "cropsight/pipeline/broccoli/config.hpp"

namespace cropsight::pipeline::broccoli {

/// Both estimators' fits (truth = scale · estimate + offset, mm) at one hull size: the means of
/// the groups' fits (n: their pairs together; RMS: the mean of the groups').
struct SizeCorrection {
  measure::BiasFit hull, bbox;
  int hull_max_points = 0;          ///< the sizing.hull_max_points the hull was fitted at (0: every point)
  std::vector<std::string> groups;  ///< the varieties fitted ("" = passes that name none)
};

/// Runs the pipeline of `model` under `cfg` (tracking on; cfg's own sizing.*_scale / *_offset_mm
/// are ignored: the fit is on raw sizes) over the labelled `sequences` and fits both estimators
/// per variety (measure::fit_size_bias: per detection on a true head), then averages the varieties. `progress(sequence,
/// frame, frames)` after every frame when given. Throws Error(sequence, ...) for a sequence without labels or
/// groundtruth.json, and Error("size calibration", ...) when too few heads of a variety were sized
/// to fit (name the variety's passes apart, or add passes of it).
SizeCorrection fit_size_correction(std::shared_ptr<const learning::Model> model, Config cfg,
                                   const std::vector<std::string>& sequences,
                                   const std::function<void(const std::string&, int, int)>& progress = {});

/// The fit as the config keys a model file records: sizing.hull_scale, sizing.hull_offset_mm,
/// sizing.bbox_scale, sizing.bbox_offset_mm and sizing.hull_max_points (the correction is only
/// right at the hull size it was fitted at).
ConfigMap size_correction_values(const SizeCorrection& fit);

}  // namespace cropsight::pipeline::broccoli
