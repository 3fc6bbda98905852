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

namespace {

PotatoBox box_of(const Detection2D& d) {
  PotatoBox b;
  b.x1 = d.x1;
  b.y1 = d.y1;
  b.x2 = d.x2;
  b.y2 = d.y2;
  b.class_id = d.class_id;
  b.score = d.score;
  return b;
}
}  // namespace

PotatoRunner::PotatoRunner(const PotatoRunnerOptions& o)
    : impl_(std::make_unique<Impl>(o.preset.empty() ? std::string("potato") : o.preset, o.sets)) {}
PotatoRunner::~PotatoRunner() = default;

PotatoFrameOut PotatoRunner::process(const FrameBuffers& frame) {
  if (frame.rgb.empty()) throw Error("frame " + std::to_string(frame.index), "has no colour image");
  const pp::FrameResult r = impl_->pipe.process(to_rgbd_frame(frame));
  PotatoFrameOut out;
  out.ms_detect = r.timer.ms("detect");
  out.ms_locate = r.timer.ms("locate");
  out.ms_track = r.timer.ms("track");
  out.ms_orient = r.timer.ms("orient");
  for (std::size_t k = 0; k < r.detections.size(); ++k) {
    PotatoBox b = box_of(r.detections[k]);
    if (k < r.ripe.size()) b.ripe = r.ripe[k];
    if (k < r.positions.size()) {
      const auto& p = r.positions[k];
      b.depth_ok = p.depth_ok;
      b.x = p.xyz.x();
      b.y = p.xyz.y();
      b.z = p.xyz.z();
    }
    out.detections.push_back(b);
  }
  const pp::HarvestTarget& t = r.target;
  PotatoHarvest& h = out.target;
  h.frame = t.frame;
  h.timestamp = t.timestamp;
  h.detection = t.detection;
  h.depth_ok = t.depth_ok;
  h.x = t.x;
  h.y = t.y;
  h.z = t.z;
  h.height = t.height;
  h.width = t.width;
  h.angle = t.angle;
  h.angle_ok = t.angle_ok;
  h.cut = t.cut;
  h.target_id = t.target_id;
  h.state = int(t.state);
  h.score = t.score;
  h.box = box_of(t.box);
  return out;
}

void PotatoRunner::reset() { impl_->pipe.reset(); }

std::vector<std::string> PotatoRunner::class_names() const { return impl_->pipe.detector_class_names(); }

}  // namespace cropsight::bridge
