#pragma once
// Refiner (OES with a model; detection.split_concave_angle_deg > 0; StageTimer "split"): a head
// that the clustering joined to a leaf at the same depth comes apart where the leaf runs into it.
// The candidates classified as no head (with detection.split_accepted, heads too; always the
// oversized ones) of split_min_points or more, scoring within split_score_window of the head
// threshold, are split along their concave creases (geometry/concave_creases.hpp, on the cloud's
// normals) into pieces of the frame's OES size range (FrameConditions::oes). The pieces are
// described and classified with the detector's own steps against the head threshold plus
// split_score_margin; a candidate one of whose pieces is a head (and, for a head, scores above
// it) is replaced by its pieces: the first takes its slot, the others are appended. A piece
// holding more than split_max_piece_fraction of its candidate is that candidate again and is not
// classified. The owner image follows the pixels. All buffers are reused from frame to frame.
#include <cstdint>
#include <vector>

#include "cropsight/pipeline/broccoli/detector_config.hpp"
#include "cropsight/pipeline/broccoli/steps/classification_step.hpp"
#include "cropsight/pipeline/broccoli/steps/description_step.hpp"
#include "cropsight/pipeline/broccoli/steps/refiner.hpp"
#include "cropsight/segmentation/segment_split.hpp"

namespace cropsight::pipeline::broccoli::steps {

class CreaseSplit final : public Refiner {
 public:
  /// `description` and `classification` are the detector's steps (they must outlive this one):
  /// the pieces get the same features and model as the clusters.
  CreaseSplit(DetectionConfig cfg, const DescriptionStep& description, ClassificationStep& classification)
      : cfg_(cfg), description_(description), classification_(classification) {}

  /// Does nothing without a model. Needs FrameState::owners (an organised clustering's).
  void refine(const RgbdFrame& frame, FrameState& state, StageTimer& timer) override;

 private:
  // Per candidate, what the split does to it.
  enum : char { kKeep = 0, kReplace = 1, kSlotTaken = 2 };

  // Chooses the candidates to split (targets_) and marks their creases.
  void mark_targets(const FrameState& state, float head_threshold);
  // Describes and classifies the pieces that may be heads (pieces_, scored_).
  void score_pieces(std::vector<segmentation::SplitPiece>& split, const FrameState& state, float threshold);
  // Puts the pieces of every candidate with a head piece in its place.
  void replace_parents(const std::vector<segmentation::SplitPiece>& split, FrameState& state, float threshold);

  DetectionConfig cfg_;
  const DescriptionStep& description_;
  ClassificationStep& classification_;
  std::vector<const Segment*> segments_;  // every candidate's segment, in order
  std::vector<int> targets_;
  std::vector<std::uint8_t> creases_;  // per pixel: 1 on a concave crease of a target
  segmentation::SegmentSplitWorkspace split_ws_;
  std::vector<Candidate> pieces_;  // a pool like the candidates'
  std::vector<Candidate*> batch_;  // the pieces classified together
  std::vector<char> replace_;      // per candidate: kKeep, kReplace or kSlotTaken
  std::vector<char> scored_;       // per piece: described and classified
};

}  // namespace cropsight::pipeline::broccoli::steps
