#pragma once
// What the model proposes on one frame of a depth sequence, for the studio's review and
// model-assisted labelling: every cluster the broccoli detector made (pixels, score, verdict),
// computed once per frame and cached. The pipeline runs without tracking (make_pipeline with
// track=false): a user jumps between frames, so there is no pass order for a temporal filter.
//
// Thread-safe: the pipeline is not, so frames are analysed one at a time under a mutex; cached
// results are shared read-only.
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"

namespace cropsight::studio {

struct CandidateView {
  std::vector<int> pixels;  ///< ascending pixel indices (y·width + x)
  float score = 0.0f;       ///< classifier score
  bool head = false;        ///< the pipeline's verdict (score above threshold + margin)
  double diameter_mm = 0;   ///< of the disc of its measured area (a size at a glance, not the sizer's)
};

struct FrameCandidates {
  int frame = 0;
  std::vector<CandidateView> candidates;
  /// How sure the model is about this frame: the smallest |score − threshold| over its
  /// candidates (score units; large = sure). Infinity for a frame without candidates.
  float certainty = 0.0f;
};

class FrameAnalyzer {
 public:
  /// `model`: a shipped model's name or a model file ("" = the default broccoli model). Throws
  /// Error naming the model when it cannot be loaded.
  FrameAnalyzer(const io::SequenceReader& reader, const std::string& model);

  /// The candidates of `frame` (analysed on first use). Throws Error naming the frame's file.
  std::shared_ptr<const FrameCandidates> analyse(int frame);
  /// The candidates of `frame` if already analysed, else null (never runs the pipeline).
  std::shared_ptr<const FrameCandidates> cached(int frame) const;
  /// The head threshold (classifier threshold + score margin), score units.
  float threshold() const { return threshold_; }
  const std::string& model_name() const { return model_name_; }
  /// The configuration the pipeline runs with (training in the studio uses the same).
  const pipeline::broccoli::Config& config() const { return pipeline_->config(); }
  std::shared_ptr<const learning::Model> model() const { return pipeline_->detector().model(); }

 private:
  const io::SequenceReader& reader_;
  std::string model_name_;
  std::unique_ptr<pipeline::broccoli::Pipeline> pipeline_;
  float threshold_ = 0.0f;
  mutable std::mutex mutex_;
  std::map<int, std::shared_ptr<const FrameCandidates>> cache_;
};

}  // namespace cropsight::studio
