#include "cropsight/pipeline/broccoli/timing.hpp"

#include "cropsight/core/error.hpp"

namespace cropsight::pipeline::broccoli {

namespace {
template <class Pipeline, class Count>
PipelineTiming time_passes(Pipeline& p, const std::vector<RgbdFrame>& frames, int repeat, Count count) {
  if (frames.empty()) throw Error("bench", "no frames to time");
  p.process(frames.front());  // warm-up: buffers sized, caches touched
  p.timer().clear();
  PipelineTiming t;
  for (int r = 0; r < repeat; ++r)
    for (const RgbdFrame& f : frames) {
      t.clusters += count(timed(t, [&] { return p.process(f); }));
      ++t.frames;
    }
  t.stages = p.timer().stages();
  return t;
}
}  // namespace

PipelineTiming time_detector(Detector& detector, const std::vector<RgbdFrame>& frames, int repeat) {
  return time_passes(detector, frames, repeat, [](std::span<const Candidate> c) { return long(c.size()); });
}

PipelineTiming time_pcl_reference(PclReferencePipeline& pcl, const std::vector<RgbdFrame>& frames, int repeat) {
  return time_passes(pcl, frames, repeat, [](std::size_t n) { return long(n); });
}

PipelineTiming time_tracking(Detector& detector, const tracking::HeadMapperConfig& cfg,
                             const std::vector<RgbdFrame>& frames, int repeat) {
  if (frames.empty()) throw Error("bench", "no frames to time");
  auto track_one = [&](tracking::HeadMapper& mapper, const RgbdFrame& f, PipelineTiming& t) {
    detector.process(f);
    std::vector<Detection> dets = detector.detections();
    timed(t, [&] {
      mapper.add_frame(f.index, detector.cloud(), dets, f.camera_position);
      return mapper.predict_missed(detector.cloud(), f.camera).size();
    });
    t.clusters += long(dets.size());
  };
  {  // warm-up: the sizer's and filter's buffers, as time_passes' first frame
    tracking::HeadMapper warm(cfg);
    PipelineTiming unused;
    track_one(warm, frames.front(), unused);
  }
  PipelineTiming t;
  for (int r = 0; r < repeat; ++r) {
    tracking::HeadMapper mapper(cfg);  // one pass: the filter starts empty
    for (const RgbdFrame& f : frames) {
      track_one(mapper, f, t);
      ++t.frames;
    }
    timed(t, [&] { return mapper.finish().size(); });
  }
  return t;
}

std::shared_ptr<const learning::Model> model_for_variant(const std::shared_ptr<const learning::Model>& model,
                                                         Variant variant, const std::string& where) {
  const std::string tag = config_name(variant);
  if (model->info.pipeline == tag) return model;
  auto shim = std::make_shared<learning::Model>();
  shim->info = model->info;
  shim->info.pipeline = tag;
  shim->standardizer = model->standardizer;
  shim->params = model->params;
  shim->classifier =
      learning::deserialize_classifier(model->params, model->info.feature_dim, model->classifier->serialize(), where);
  return shim;
}

}  // namespace cropsight::pipeline::broccoli
