// The model's candidates per frame, cached (studio/frame_candidates.hpp).
#include "cropsight/studio/frame_candidates.hpp"

#include <cmath>
#include <limits>

#include "cropsight/pipeline/broccoli/make_pipeline.hpp"
#include "studio/head_geometry.hpp"

namespace cropsight::studio {

FrameAnalyzer::FrameAnalyzer(const io::SequenceReader& reader, const std::string& model)
    : reader_(reader), model_name_(model.empty() ? pipeline::broccoli::kDefaultModel : model) {
  pipeline_ = pipeline::broccoli::make_pipeline({.sets = {"track=false"}, .model = model_name_});
  threshold_ = pipeline_->detector().model()->threshold() + pipeline_->config().detector.detection.score_margin;
}

std::shared_ptr<const FrameCandidates> FrameAnalyzer::cached(int frame) const {
  std::lock_guard lock(mutex_);
  const auto it = cache_.find(frame);
  return it == cache_.end() ? nullptr : it->second;
}

std::shared_ptr<const FrameCandidates> FrameAnalyzer::analyse(int frame) {
  std::lock_guard lock(mutex_);
  if (const auto it = cache_.find(frame); it != cache_.end()) return it->second;
  RgbdFrame f = reader_.read(frame);
  f.labels = {};  // the model's view only: labels never reach the pipeline
  pipeline_->process(f);
  auto out = std::make_shared<FrameCandidates>();
  out->frame = frame;
  out->certainty = std::numeric_limits<float>::infinity();
  for (const auto& c : pipeline_->detector().candidates()) {
    if (c.segment.indices.empty()) continue;
    out->candidates.push_back(
        {c.segment.indices, c.score, c.head, head_geometry(c.segment.indices, f.depth, f.camera).diameter_mm});
    out->certainty = std::min(out->certainty, std::abs(c.score - threshold_));
  }
  cache_[frame] = out;
  return out;
}

}  // namespace cropsight::studio
