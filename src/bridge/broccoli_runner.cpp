#include "cropsight/bridge/broccoli_runner.hpp"

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"
#include "cropsight/tracking/field_map_io.hpp"
#include "frame_conversion.hpp"

namespace cropsight::bridge {

namespace {
pipeline::PipelineSpec spec_of(const BroccoliRunnerOptions& o) {
  pipeline::PipelineSpec spec{o.preset, o.sets, o.model};
  spec.sets.push_back(o.track ? "track=true" : "track=false");
  return spec;
}

}  // namespace

// The pipeline is neither copyable nor movable: the library's builder returns it on the heap.
struct BroccoliRunner::Impl {
  std::unique_ptr<pipeline::broccoli::Pipeline> built;
  pipeline::broccoli::Pipeline& pipe;
  explicit Impl(const BroccoliRunnerOptions& o) : built(pipeline::broccoli::make_pipeline(spec_of(o))), pipe(*built) {
    // A node runs for hours and never scores a pass offline: keeping every measured detection
    // would grow its memory with the frames (docs/reliability.md, "Long runs").
    pipe.set_record_detections(false);
  }
};

BroccoliRunner::BroccoliRunner(const BroccoliRunnerOptions& options) : impl_(std::make_unique<Impl>(options)) {}
BroccoliRunner::~BroccoliRunner() = default;

pipeline::broccoli::FrameResult BroccoliRunner::process(const FrameBuffers& frame) {
  if (frame.depth.empty()) throw Error("frame " + std::to_string(frame.index), "has no depth image");
  return impl_->pipe.process(to_rgbd_frame(frame));
}

std::vector<tracking::TrackedHead> BroccoliRunner::current_map() const {
  std::vector<tracking::TrackedHead> out;
  if (!impl_->pipe.config().track) return out;
  const tracking::TemporalFilter& filter = impl_->pipe.mapper().filter();
  for (const auto& h : filter.all_heads())
    if (filter.confirmed_now(h)) out.push_back(h);
  return out;
}

void BroccoliRunner::finish_and_write_map(const std::string& csv_path) {
  if (!impl_->pipe.config().track) throw Error(csv_path, "the field map needs tracking (track = true)");
  tracking::write_field_map(csv_path, impl_->pipe.finish());
  impl_->pipe.reset();
}

bool BroccoliRunner::tracking() const { return impl_->pipe.config().track; }

std::string BroccoliRunner::pipeline_name() const { return config_name(impl_->pipe.config().detector.pipeline); }

}  // namespace cropsight::bridge
