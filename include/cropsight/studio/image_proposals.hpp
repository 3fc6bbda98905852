#pragma once
// What a model proposes on one image of a folder, for the studio's pre-filled boxes, computed
// once per image and cached. Either the potato pipeline's 2D detection step (make_pipeline, then
// Pipeline::detect_image: what `detect potato --images` runs), or the project's own 2D detector
// (CenterNet, as `detect objects` and `train detector` know it: the shipped detector-grape, or a
// model a user trained on the studio's labels). The user's saved labels always win: the page
// shows proposals only on images nobody saved yet.
//
// Thread-safe: detectors are not, so images are detected one at a time under a mutex.
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "cropsight/core/box2d.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/pipeline/potato/pipeline.hpp"

namespace cropsight::studio {

class ImageProposals {
 public:
  /// `detector` (a shipped model's name, a .onnx or a .pt file): the project's 2D detector.
  /// Else the potato pipeline, with `model` ("" = the potato preset's own detector) an ONNX
  /// detector run in its place, as `detect potato --model`. Throws Error naming the model or
  /// preset when it cannot be loaded.
  ImageProposals(const std::string& model, const std::string& detector);
  ~ImageProposals();

  /// The detector's boxes on `image` (pixels, highest score first), detected on first use.
  /// Throws Error naming the file when it cannot be read.
  std::vector<Detection2D> detect(int index, const std::filesystem::path& image);
  /// Whether `index` was detected already (never runs the detector).
  bool cached(int index) const;
  /// Detection2D::class_id indexes these.
  const std::vector<std::string>& class_names() const { return classes_; }
  /// What the page shows as the model: "potato", or the --model or --detector given.
  const std::string& model_name() const { return model_name_; }

 private:
  std::string model_name_;
  std::unique_ptr<pipeline::potato::Pipeline> pipeline_;  // or
  std::unique_ptr<Detector2D> detector_;
  std::vector<std::string> classes_;
  mutable std::mutex mutex_;
  std::map<int, std::vector<Detection2D>> cache_;
};

}  // namespace cropsight::studio
