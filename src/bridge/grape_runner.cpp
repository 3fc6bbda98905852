#include "cropsight/bridge/grape_runner.hpp"

#include <algorithm>
#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/grape/make_pipeline.hpp"
#include "cropsight/pipeline/grape/pipeline.hpp"
#include "frame_conversion.hpp"

namespace cropsight::bridge {

namespace {

// The pipeline as every front-end builds it (pipeline::grape::make_pipeline). pipeline::grape::Pipeline moves.
pipeline::grape::Pipeline make_runner_pipeline(const GrapeRunnerOptions& o) {
  return std::move(*pipeline::grape::make_pipeline({o.config, o.sets, o.segmenter, o.detector, o.threads}));
}

GrapeBox box_of(const Box2D& b, int category, float score) { return {b.x, b.y, b.width, b.height, category, score}; }

GrapeBunchOut bunch_of(const pipeline::grape::Bunch& b) {
  GrapeBunchOut out;
  out.roi = box_of(b.roi, 1, 1.f);
  const Cloud& c = b.cloud;
  out.xyz.reserve(3 * c.size());
  for (const auto& p : c.points) out.xyz.insert(out.xyz.end(), {p.x(), p.y(), p.z()});
  if (c.has_colors()) {
    out.rgb.reserve(3 * c.size());
    for (const auto& col : c.colors)
      for (int k = 0; k < 3; ++k) out.rgb.push_back(std::uint8_t(std::lround(std::clamp(col[k], 0.f, 1.f) * 255.f)));
  }
  out.labels = c.labels;
  if (b.cut_point) {
    out.has_cut_point = true;
    for (int k = 0; k < 3; ++k) {
      out.cut_position[k] = b.cut_point->position[k];
      out.cut_direction[k] = b.cut_point->direction[k];
    }
    out.cut_confidence = b.cut_point->confidence;
  }
  return out;
}

GrapeFrameOut frame_out(const pipeline::grape::FrameResult& r) {
  GrapeFrameOut out;
  for (const auto& d : r.detections) out.detections.push_back(box_of(d.box, d.category, d.score));
  for (const auto& b : r.bunches) out.bunches.push_back(bunch_of(b));
  return out;
}

}  // namespace

// The pipeline owns its segmenter and detector (models loaded once, here).
struct GrapeRunner::Impl {
  pipeline::grape::Pipeline pipe;
  explicit Impl(const GrapeRunnerOptions& o) : pipe(make_runner_pipeline(o)) {}
};

GrapeRunner::GrapeRunner(const GrapeRunnerOptions& options) : impl_(std::make_unique<Impl>(options)) {}
GrapeRunner::~GrapeRunner() = default;

GrapeFrameOut GrapeRunner::process(const FrameBuffers& frame) {
  if (frame.rgb.empty()) throw Error("frame " + std::to_string(frame.index), "has no colour image");
  return frame_out(impl_->pipe.process(to_rgbd_frame(frame)));
}

GrapeFrameOut GrapeRunner::process(const FrameBuffers& frame, const std::vector<GrapeInputBox>& boxes) {
  if (frame.rgb.empty()) throw Error("frame " + std::to_string(frame.index), "has no colour image");
  // As the project's detector's boxes: class_id = category - 1 (pipeline::grape::grape_detections adds it back).
  std::vector<Detection2D> given;
  for (const GrapeInputBox& b : boxes)
    given.push_back({float(b.x1), float(b.y1), float(b.x2), float(b.y2), b.category - 1, b.score});
  return frame_out(impl_->pipe.process(to_rgbd_frame(frame), pipeline::grape::grape_detections(given)));
}

bool GrapeRunner::has_detector() const { return impl_->pipe.has_detector(); }

std::string GrapeRunner::segmenter_model() const { return impl_->pipe.segmenter().config().model; }

}  // namespace cropsight::bridge
