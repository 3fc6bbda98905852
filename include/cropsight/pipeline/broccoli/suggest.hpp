#pragma once
// Which frames of a sequence to label next (active learning for the broccoli head classifier):
// frames are ranked, best first, by how unsure the model is about them (uncertainty) and by how
// little they resemble the frames already chosen (diversity), so that a user who labels the first
// N frames of the ranking gives the trainer clusters it cannot yet tell apart, from different parts
// of the field, rather than N near-copies of one view.
//
//   1. per frame (measure_frame): every described candidate's distance from the head threshold,
//      |score − (model threshold + detection.score_margin)| in score units, becomes a weight
//      exp(−distance / score_scale) in (0, 1]; the frame's uncertainty is their sum (a frame with
//      many doubtful clusters teaches more than one with a single doubtful cluster). Its heads are
//      the candidates at or above the threshold (what the model takes for heads). Its descriptor
//      is a histogram of the frame's valid depths (what the view looks like: canopy, soil, rows),
//      cheap and independent of the model.
//   2. greedy ranking (rank_frames): each step takes the frame with the largest
//        gain = (floor + uncertainty / max uncertainty + heads_weight × heads / max heads)
//               × (1 − diversity_weight × similarity),
//      where similarity to the chosen frames is the largest of exp(−|index gap| / neighbour_frames)
//      (neighbouring frames of a pass overlap) and exp(−descriptor distance / typical distance)
//      (the median distance between frames, so that the scale suits every sequence).
//
// No ground truth is read. Deterministic: ties go to the lower frame index.
#include <functional>
#include <span>
#include <vector>

#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/candidate.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"

namespace cropsight::pipeline::broccoli {

struct SuggestConfig {
  int frames = 10;                ///< how many frames to rank (clamped to the sequence's length)
  float score_scale = 0.5f;       ///< score units: a candidate this far from the threshold weighs 1/e
  double neighbour_frames = 3.0;  ///< frames: index gap at which a neighbour's similarity falls to 1/e
  double diversity_weight = 0.8;  ///< 0 = uncertainty only; 1 = a frame like a chosen one gains nothing
  double floor = 0.05;            ///< gain of a frame without doubtful clusters, so that ties still spread
  int depth_bins = 24;            ///< descriptor: depth histogram bins over [min_depth_m, max_depth_m]
  double min_depth_m = 0.3;
  double max_depth_m = 2.0;
  /// Weight of the frame's predicted heads against its uncertainty: every frame holds many
  /// not-head clusters (leaves, soil, weeds) but few heads, so a model trained on a few frames is
  /// short of heads. 1 (heads count as much as doubt) was chosen on two simulated field kinds and
  /// judged on two others (docs/adapting.md); 0 = the earlier rule, uncertainty only.
  double heads_weight = 1.0;
  /// Throws Error(where, ...) naming the first bad value.
  void validate(const char* where) const;
};

/// What step 1 measured on one frame.
struct FrameUncertainty {
  int frame = 0;
  double uncertainty = 0.0;       ///< sum of the candidates' weights (see the header comment)
  double max_weight = 0.0;        ///< the most doubtful candidate's weight, in [0, 1]
  int candidates = 0;             ///< described candidates scored
  int doubtful = 0;               ///< candidates within score_scale of the threshold
  int heads = 0;                  ///< candidates scoring at or above the threshold
  std::vector<float> descriptor;  ///< normalised depth histogram (sums to 1; all 0 when no valid depth)
};

/// One ranked frame.
struct SuggestedFrame {
  int frame = 0;
  double gain = 0.0;  ///< the greedy gain when it was chosen (step 2), in [0, 1 + floor + heads_weight]
  FrameUncertainty measured;
};

/// Step 1 on the candidates the detector returned for `frame` (their scores against `threshold`).
FrameUncertainty measure_frame(int index, const RgbdFrame& frame, std::span<const Candidate> candidates,
                               float threshold, const SuggestConfig& cfg);

/// Step 2: the first cfg.frames frames of the ranking, best first.
std::vector<SuggestedFrame> rank_frames(const std::vector<FrameUncertainty>& frames, const SuggestConfig& cfg);

/// Steps 1 and 2 over every frame of `sequence` with `pipe` (built by make_pipeline; it needs a
/// model). `progress(done, total)` is called after each frame when given. Throws Error naming the
/// sequence when it has no frame, Error("model", ...) when the pipeline has no model.
std::vector<SuggestedFrame> suggest_frames(Pipeline& pipe, const io::SequenceReader& sequence, const SuggestConfig& cfg,
                                           const std::function<void(int, int)>& progress = {});

}  // namespace cropsight::pipeline::broccoli
