#include "cropsight/pipeline/broccoli/pipeline.hpp"

#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"

namespace cropsight::pipeline::broccoli {

namespace {
// The whole config is checked before any step is built from it, so that an error names the key.
const DetectorConfig& validated_detector(const Config& cfg, const std::string& where) {
  cfg.validate(where);
  return cfg.detector;
}
}  // namespace

void Config::validate(const std::string& where) const {
  detector.validate(where);
  truth.validate(where);
  tracking::HeadMapper check(mapping());  // sizing.* and tracking.* are checked where they are used
}

std::shared_ptr<const learning::Model> load_model(const std::filesystem::path& path) {
  auto m = std::make_shared<learning::Model>(learning::load_model(path));
  if (m->info.task != kBroccoliTask)
    throw Error(path.string(), "model was trained for task '" + m->info.task + "', not broccoli heads");
  return m;
}

Config config_for_model(const learning::Model& model, const ConfigMap& overrides, const std::string& where,
                        const std::string& overrides_where) {
  Config cfg;
  apply_config(cfg, model.info.config, where);
  apply_config(cfg, overrides, overrides_where);
  cfg.validate(where);
  return cfg;
}

Pipeline::Pipeline(const Config& cfg, std::shared_ptr<const learning::Model> model, const std::string& where)
    : cfg_(cfg), detector_(validated_detector(cfg, where)) {
  if (!model) throw Error(where, "the broccoli pipeline needs a model");
  detector_.set_model(std::move(model), where);
  reset();
}

void Pipeline::reset() {
  if (!cfg_.track) return;
  mapper_.emplace(cfg_.mapping());
  mapper_->set_record_detections(record_detections_);
}

void Pipeline::set_record_detections(bool on) {
  record_detections_ = on;
  if (mapper_) mapper_->set_record_detections(on);
}

FrameResult Pipeline::process(const RgbdFrame& frame) {
  FrameResult& r = result_;
  r.frame = frame.index;
  r.predicted.clear();
  r.association = {};
  const std::vector<StageTimer::Stage> before = detector_.timer().stages();
  detector_.process(frame);  // 1. cloud → normals → clusters → features → classifier
  r.detections = detector_.detections();
  r.timer = detector_.timer().since(before);
  if (mapper_) {
    auto t = r.timer.scope("track");
    // 2. + 3. size every whole head, then the temporal filter (sets size_m and track_id)
    r.association = mapper_->add_frame(frame.index, detector_.cloud(), r.detections, frame.camera_position);
    r.predicted = mapper_->predict_missed(detector_.cloud(), frame.camera);  // 4. heads this frame missed
  }
  return r;
}

const std::vector<tracking::TrackedHead>& Pipeline::finish() { return mapper_ ? mapper_->finish() : no_map_; }

const tracking::HeadMapper& Pipeline::mapper() const {
  if (!mapper_) throw Error("broccoli pipeline", "tracking is off (track = false): there is no head mapper");
  return *mapper_;
}

}  // namespace cropsight::pipeline::broccoli
