// The potato detector's boxes per image, cached (studio/image_proposals.hpp).
#include "cropsight/studio/image_proposals.hpp"

#include "cropsight/io/config_yaml.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "cropsight/pipeline/potato/make_pipeline.hpp"

namespace cropsight::studio {

ImageProposals::ImageProposals(const std::string& model, const std::string& detector) {
  if (!detector.empty()) {
    model_name_ = detector;
    detector_ = nn::load_center_detector(io::find_model(detector));
    classes_ = detector_->class_names();
    return;
  }
  model_name_ = model.empty() ? pipeline::potato::kDefaultPreset : model;
  pipeline_ = pipeline::potato::make_pipeline({.model = model});
  classes_ = pipeline_->detector_class_names();
}

ImageProposals::~ImageProposals() = default;

std::vector<Detection2D> ImageProposals::detect(int index, const std::filesystem::path& image) {
  std::lock_guard lock(mutex_);
  if (const auto it = cache_.find(index); it != cache_.end()) return it->second;
  const ColorImage color = io::read_color(image);
  if (detector_) return cache_[index] = detector_->detect({&color, nullptr});
  auto result = pipeline_->detect_image(color, {}, /*orient_boxes=*/false);
  return cache_[index] = std::move(result.detections);
}

bool ImageProposals::cached(int index) const {
  std::lock_guard lock(mutex_);
  return cache_.count(index) != 0;
}

}  // namespace cropsight::studio
