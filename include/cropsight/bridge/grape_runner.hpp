#pragma once
// The grape pipeline from the camera (pipeline::grape::Pipeline, Luo et al.) behind a C++17 header,
// for the ROS node: bunch and peduncle boxes (the project's detector, or boxes given per frame)
// → ROI (Eq. 1, overlapping bunches merged) → coloured ROI cloud → normals → the grape segmenter
// → per bunch a labelled cloud and a cut point on its peduncle: the library's own FrameResult
// (pipeline/grape/frame_result.hpp, C++17). One runner per camera; not thread-safe. Errors: cropsight::Error naming the
// file or input.
//
// Pixels: x = column, y = row, origin top-left. Points: camera frame (x right, y down, z forward),
// metres.
#include <memory>
#include <string>
#include <vector>

#include "cropsight/bridge/frame_buffers.hpp"
#include "cropsight/pipeline/grape/frame_result.hpp"

namespace cropsight::bridge {

struct GrapeRunnerOptions {
  std::string config;                    ///< pipeline preset (name under configs/ or YAML); "" = grape-camera
  std::vector<std::string> sets;         ///< "key=value" overrides of the pipeline preset (roi.*, cut_point.*)
  std::string segmenter = "grape-best";  ///< segmenter preset (name or YAML) or model file (.pt, .json)
  std::string detector;                  ///< the project's grape detector (.onnx or .pt); "" = boxes given to process()
  int threads = 2;                       ///< threads of the segmenter and a .pt detector
};

/// A box of the user's own detector, continuous pixel corners; the pipeline takes the pixel box
/// that covers it, as it takes the project's detector's boxes (pipeline::grape::grape_detections).
struct GrapeInputBox {
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;  ///< pixels
  int category = 1;                       ///< 1 bunch, 2 peduncle (the dataset's COCO categories)
  float score = 1;
};

class GrapeRunner {
 public:
  /// Loads and validates the presets and the models. Throws Error(file or "--set", ...).
  explicit GrapeRunner(const GrapeRunnerOptions& options);
  ~GrapeRunner();
  GrapeRunner(const GrapeRunner&) = delete;
  GrapeRunner& operator=(const GrapeRunner&) = delete;

  /// One frame (colour required, registered to depth), boxes from the detector. Throws Error
  /// when the runner has no detector or the frame is malformed.
  pipeline::grape::FrameResult process(const FrameBuffers& frame);
  /// One frame on the boxes given (a detector of the user's).
  pipeline::grape::FrameResult process(const FrameBuffers& frame, const std::vector<GrapeInputBox>& boxes);
  bool has_detector() const;
  /// The segmenter's model file, for logs.
  std::string segmenter_model() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cropsight::bridge
