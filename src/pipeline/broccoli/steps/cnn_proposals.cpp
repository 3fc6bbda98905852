#include "cropsight/pipeline/broccoli/steps/cnn_proposals.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <limits>
#include <string>
#include <utility>

#include "cropsight/core/error.hpp"
#include "cropsight/eval/detection_ap.hpp"  // point_set_iou
#include "cropsight/nn/center_decode.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "cropsight/pipeline/broccoli/depth_encoding.hpp"

namespace cropsight::pipeline::broccoli::steps {

namespace {
// Whether `pixels` overlap an accepted head (or an earlier proposal) by more than `max_overlap`.
bool duplicates_a_head(const std::vector<int>& pixels, const CandidatePool& pool, float max_overlap) {
  const auto heads = pool.active();
  return std::any_of(heads.begin(), heads.end(), [&](const Candidate& c) {
    return c.head && eval::point_set_iou(pixels, c.segment.indices) > max_overlap;
  });
}
}  // namespace

CnnProposals::CnnProposals(CnnConfig cfg, const ClassificationStep& classification)
    : cfg_(std::move(cfg)), classification_(classification) {
  if (std::filesystem::path(cfg_.model).extension() != ".onnx")
    throw Error(cfg_.model, "cnn.model must be an .onnx file (cropsight export-detector)");
  cnn_ = std::make_unique<nn::CenterNetOnnx>(cfg_.model);
  if (cnn_->class_names() != std::vector<std::string>{"head"})
    throw Error(cfg_.model, "cnn.model must be a detector of the one class 'head'");
}

CnnProposals::~CnnProposals() = default;

void CnnProposals::refine(const RgbdFrame& frame, FrameState& state, StageTimer& timer) {
  auto t = timer.scope("cnn");
  const ColorImage image = encode_depth_for_cnn(frame.depth, frame.camera.depth_scale);
  const nn::CenterNetHeads heads = cnn_->heads(image);  // one run: boxes and masks from it
  const nn::CenterNetConfig& net = cnn_->config();
  const std::vector<Detection2D> boxes = nn::boxes_from_heads(heads, net, image.width, image.height);
  const std::vector<GrayImage> masks = nn::masks_from_heads(heads, net, image.width, image.height);
  // Ranks every proposal after the classifier's heads (scores above the threshold), in the CNN's order.
  const float head = classification_.head_threshold();
  for (const Detection2D& b : boxes) {  // highest score first
    if (b.score < cfg_.min_score) break;
    std::vector<int> pixels = mask_points_in_box(b, masks.front(), state.cloud.z);  // ascending, as Segment's
    if (int(pixels.size()) < cfg_.min_points || duplicates_a_head(pixels, state.candidates, cfg_.max_overlap)) continue;
    take_pixels(pixels, state);
    Candidate& c = state.candidates.append();
    c.segment.indices = std::move(pixels);
    summarize(c.segment, state.cloud);
    c.features.clear();
    c.normal_points = -1;
    c.described = false;
    c.oversized = false;
    c.proposed = true;
    c.head = true;
    c.score = std::nextafter(head, std::numeric_limits<float>::infinity()) + 1e-3f * b.score;
  }
}

// The proposal is a head the clustering joined to leaves: the remainder keeps its rejection.
void CnnProposals::take_pixels(const std::vector<int>& pixels, FrameState& state) {
  CandidatePool& pool = state.candidates;
  for (Candidate& c : pool.active()) {
    Segment& s = c.segment;
    if (c.head || !eval::point_set_iou(pixels, s.indices)) continue;
    rest_.clear();
    std::set_difference(s.indices.begin(), s.indices.end(), pixels.begin(), pixels.end(), std::back_inserter(rest_));
    s.indices.swap(rest_);
    summarize(s, state.cloud);
  }
  // A candidate the proposal took whole is gone (the pool's last candidate takes its slot).
  for (std::size_t k = 0; k < pool.size();)
    if (pool[k].segment.indices.empty())
      pool.remove(k);
    else
      ++k;
}

}  // namespace cropsight::pipeline::broccoli::steps
