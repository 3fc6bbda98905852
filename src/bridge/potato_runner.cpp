#include "cropsight/bridge/potato_runner.hpp"

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/potato/make_pipeline.hpp"
#include "cropsight/pipeline/potato/pipeline.hpp"
#include "frame_conversion.hpp"

namespace cropsight::bridge {

namespace pp = pipeline::potato;

struct PotatoRunner::Impl {
  std::unique_ptr<pp::Pipeline> built;
  pp::Pipeline& pipe;
  explicit Impl(const std::string& preset, const std::vector<std::string>& sets)
      : built(pp::make_pipeline({preset, sets})), pipe(*built) {}
};

PotatoRunner::PotatoRunner(const PotatoRunnerOptions& o)
    : impl_(std::make_unique<Impl>(o.preset.empty() ? std::string("potato") : o.preset, o.sets)) {}
PotatoRunner::~PotatoRunner() = default;

pipeline::potato::FrameResult PotatoRunner::process(const FrameBuffers& frame) {
  if (frame.rgb.empty()) throw Error("frame " + std::to_string(frame.index), "has no colour image");
  return impl_->pipe.process(to_rgbd_frame(frame));
}

void PotatoRunner::reset() { impl_->pipe.reset(); }

std::vector<std::string> PotatoRunner::class_names() const { return impl_->pipe.detector_class_names(); }

}  // namespace cropsight::bridge
