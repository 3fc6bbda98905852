#include "cropsight/bridge/grape_runner.hpp"

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

}  // namespace

// The pipeline owns its segmenter and detector (models loaded once, here).
struct GrapeRunner::Impl {
  pipeline::grape::Pipeline pipe;
  explicit Impl(const GrapeRunnerOptions& o) : pipe(make_runner_pipeline(o)) {}
};

GrapeRunner::GrapeRunner(const GrapeRunnerOptions& options) : impl_(std::make_unique<Impl>(options)) {}
GrapeRunner::~GrapeRunner() = default;

pipeline::grape::FrameResult GrapeRunner::process(const FrameBuffers& frame) {
  if (frame.rgb.empty()) throw Error("frame " + std::to_string(frame.index), "has no colour image");
  return impl_->pipe.process(to_rgbd_frame(frame));
}

pipeline::grape::FrameResult GrapeRunner::process(const FrameBuffers& frame, const std::vector<GrapeInputBox>& boxes) {
  if (frame.rgb.empty()) throw Error("frame " + std::to_string(frame.index), "has no colour image");
  // As the project's detector's boxes: class_id = category - 1 (pipeline::grape::grape_detections adds it back).
  std::vector<Detection2D> given;
  for (const GrapeInputBox& b : boxes)
    given.push_back({float(b.x1), float(b.y1), float(b.x2), float(b.y2), b.category - 1, b.score});
  return impl_->pipe.process(to_rgbd_frame(frame), pipeline::grape::grape_detections(given));
}

bool GrapeRunner::has_detector() const { return impl_->pipe.has_detector(); }

std::string GrapeRunner::segmenter_model() const { return impl_->pipe.segmenter().config().model; }

}  // namespace cropsight::bridge
