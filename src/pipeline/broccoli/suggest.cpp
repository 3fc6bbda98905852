#include "cropsight/pipeline/broccoli/suggest.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "cropsight/core/error.hpp"

namespace cropsight::pipeline::broccoli {

namespace suggest_detail {

// Total variation distance of two normalised histograms, in [0, 1].
double descriptor_distance(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) sum += std::abs(double(a[i]) - double(b[i]));
  return 0.5 * sum;
}

// The median distance between frames: the scale at which two views count as alike. Frames are
// subsampled to at most 200 so that a long pass costs no more than a short one.
double typical_distance(const std::vector<FrameUncertainty>& frames) {
  const std::size_t step = std::max<std::size_t>(1, frames.size() / 200);
  std::vector<double> d;
  for (std::size_t i = 0; i < frames.size(); i += step)
    for (std::size_t j = i + step; j < frames.size(); j += step)
      d.push_back(descriptor_distance(frames[i].descriptor, frames[j].descriptor));
  if (d.empty()) return 1.0;
  std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(d.size() / 2), d.end());
  const double median = d[d.size() / 2];
  return median > 1e-9 ? median : 1.0;  // identical views: any positive scale says "alike"
}

std::vector<float> depth_histogram(const RgbdFrame& frame, const SuggestConfig& cfg) {
  std::vector<float> hist(std::size_t(cfg.depth_bins), 0.0f);
  const double scale = frame.camera.depth_scale;
  const double width = (cfg.max_depth_m - cfg.min_depth_m) / cfg.depth_bins;
  double total = 0.0;
  for (const std::uint16_t raw : frame.depth.data) {
    const double z = raw * scale;
    if (raw == 0 || z < cfg.min_depth_m || z >= cfg.max_depth_m) continue;
    hist[std::size_t((z - cfg.min_depth_m) / width)] += 1.0f;
    total += 1.0;
  }
  if (total > 0)
    for (float& h : hist) h = float(h / total);
  return hist;
}

}  // namespace suggest_detail

void SuggestConfig::validate(const char* where) const {
  auto bad = [&](const std::string& what) { throw Error(where, what); };
  if (frames < 1) bad("frames must be >= 1, got " + std::to_string(frames));
  if (!(score_scale > 0)) bad("score_scale must be > 0 (score units)");
  if (!(neighbour_frames > 0)) bad("neighbour_frames must be > 0");
  if (!(diversity_weight >= 0 && diversity_weight <= 1)) bad("diversity_weight must lie in [0, 1]");
  if (!(floor >= 0)) bad("floor must be >= 0");
  if (!(heads_weight >= 0)) bad("heads_weight must be >= 0");
  if (depth_bins < 1) bad("depth_bins must be >= 1");
  if (!(min_depth_m >= 0 && max_depth_m > min_depth_m)) bad("need 0 <= min_depth_m < max_depth_m");
}

FrameUncertainty measure_frame(int index, const RgbdFrame& frame, std::span<const Candidate> candidates,
                               float threshold, const SuggestConfig& cfg) {
  FrameUncertainty u;
  u.frame = index;
  for (const Candidate& c : candidates) {
    // Not described: never classified (its score is a sentinel); proposed: the CNN's, not the model's.
    if (!c.described || c.proposed) continue;
    const double distance = std::abs(double(c.score) - double(threshold));
    const double weight = std::exp(-distance / cfg.score_scale);
    u.uncertainty += weight;
    u.max_weight = std::max(u.max_weight, weight);
    ++u.candidates;
    if (distance <= cfg.score_scale) ++u.doubtful;
    if (c.score >= threshold) ++u.heads;
  }
  u.descriptor = suggest_detail::depth_histogram(frame, cfg);
  return u;
}

std::vector<SuggestedFrame> rank_frames(const std::vector<FrameUncertainty>& frames, const SuggestConfig& cfg) {
  cfg.validate("suggest");
  const std::size_t n = frames.size(), want = std::min(n, std::size_t(cfg.frames));
  double top = 0.0;
  int top_heads = 0;
  for (const auto& f : frames) top = std::max(top, f.uncertainty), top_heads = std::max(top_heads, f.heads);
  const double scale = suggest_detail::typical_distance(frames);
  std::vector<double> similarity(n, 0.0);  // to the frames chosen so far
  std::vector<bool> chosen(n, false);
  std::vector<SuggestedFrame> out;
  while (out.size() < want) {
    std::size_t best = n;
    double best_gain = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      if (chosen[i]) continue;
      const double heads = top_heads > 0 ? cfg.heads_weight * frames[i].heads / top_heads : 0.0;
      const double gain = (cfg.floor + (top > 0 ? frames[i].uncertainty / top : 0.0) + heads) *
                          (1.0 - cfg.diversity_weight * similarity[i]);
      if (gain > best_gain) best = i, best_gain = gain;  // strict: ties keep the lower index
    }
    chosen[best] = true;
    out.push_back({frames[best].frame, best_gain, frames[best]});
    for (std::size_t i = 0; i < n; ++i) {
      const double gap = std::abs(frames[i].frame - frames[best].frame);
      const double d = suggest_detail::descriptor_distance(frames[i].descriptor, frames[best].descriptor);
      const double s = std::max(std::exp(-gap / cfg.neighbour_frames), std::exp(-d / scale));
      similarity[i] = std::max(similarity[i], s);
    }
  }
  return out;
}

std::vector<SuggestedFrame> suggest_frames(Pipeline& pipe, const io::SequenceReader& sequence, const SuggestConfig& cfg,
                                           const std::function<void(int, int)>& progress) {
  cfg.validate("suggest");
  if (sequence.size() == 0) throw Error(sequence.info().dir.string(), "sequence has no frames to suggest from");
  const auto& model = pipe.detector().model();
  if (!model) throw Error("model", "suggest needs a trained model to score the clusters");
  const float threshold = model->threshold() + pipe.config().detector.detection.score_margin;
  std::vector<FrameUncertainty> measured;
  pipe.reset();
  for (int i = 0; i < sequence.size(); ++i) {
    RgbdFrame frame = sequence.read(i);
    frame.labels = {};  // the ranking must not depend on labels a sequence may already carry
    pipe.process(frame);
    measured.push_back(measure_frame(i, frame, pipe.detector().candidates(), threshold, cfg));
    if (progress) progress(i + 1, sequence.size());
  }
  return rank_frames(measured, cfg);
}

}  // namespace cropsight::pipeline::broccoli
