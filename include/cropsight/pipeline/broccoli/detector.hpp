#pragma once
// Detector: the broccoli head pipelines of Montes et al. 2020, one frame at a time, composed of
// steps (steps/*.hpp), each with its own config slice and buffers, that hand on one frame state
// (steps/frame_state.hpp: the cloud, the owner image, the candidate pool):
//
//   depth image → [denoise.above > 0: a frame noisier than that is bilateral-filtered]
//     → organised cloud (metres, camera frame) → depth-range filter     steps/cloud_step.hpp
//     → integral-image normals                                          steps/normals_step.hpp
//     → OES: organised edges + flood fill bounded by edges              steps/edges_step.hpp,
//       ORG: flood fill on normal angle, grown from low-curvature points  steps/clustering_step.hpp
//       FEC: [statistical outlier removal] + Euclidean clustering (k-d tree)
//     → features per cluster (VFH [, viewpoint angle, geometric, CVFH])  steps/description_step.hpp
//     → classifier score (SVM decision value / KNN vote)                 steps/classification_step.hpp
//     → refiners, in this order, each when its option is on:
//       [detection.split_concave_angle_deg > 0: rejected clusters split at concave creases, pieces
//        classified]                                                     steps/crease_split.hpp
//       [detection.grow_tolerance > 0: head masks grown over unclustered debris]
//                                                                         steps/head_completion.hpp
//       [cnn.model: heads the depth CNN finds where no accepted head lies] steps/cnn_proposals.hpp
//     → detections
//
// Every stage is timed (StageTimer, names: "cloud", "normals", "edges", "outliers",
// "clustering", "features", "classify", "split", "completion", "cnn"; "denoise", the noise
// estimate and filter, is timed inside "cloud"). OES needs no normals to segment (unless crease
// edges are on): it computes them after the flood fill, only for the pixels of the kept segments
// (the only ones the features read), so its cloud() has NaN normals elsewhere. All buffers
// (cloud, normals' integral images, edge labels, flood-fill stacks, feature vectors, candidate
// pool) live in the steps and the frame state and are reused from frame to frame: after the first
// frame of a given size, the stages allocate only what the segmentation functions return (the
// segments' index lists).
//
// Not thread-safe: one detector per thread.
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cropsight/core/detection.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/candidate.hpp"
#include "cropsight/pipeline/broccoli/detector_config.hpp"
#include "cropsight/pipeline/broccoli/steps/classification_step.hpp"
#include "cropsight/pipeline/broccoli/steps/cloud_step.hpp"
#include "cropsight/pipeline/broccoli/steps/clustering_step.hpp"
#include "cropsight/pipeline/broccoli/steps/description_step.hpp"
#include "cropsight/pipeline/broccoli/steps/edges_step.hpp"
#include "cropsight/pipeline/broccoli/steps/frame_state.hpp"
#include "cropsight/pipeline/broccoli/steps/normals_step.hpp"
#include "cropsight/pipeline/broccoli/steps/refiner.hpp"

namespace cropsight::pipeline::broccoli {

/// Task name recorded in model files.
inline constexpr const char* kBroccoliTask = "broccoli-heads";

class Detector {
 public:
  /// Validates the config; throws Error("config", ...) when it is invalid, and Error(cnn.model,
  /// ...) when the head CNN cannot be loaded.
  explicit Detector(DetectorConfig cfg);
  ~Detector();
  Detector(const Detector&) = delete;
  Detector& operator=(const Detector&) = delete;

  const DetectorConfig& config() const { return cfg_; }
  std::size_t feature_dimension() const { return description_.dimension(); }

  /// Uses `model` to score clusters. Throws Error(where, ...) when it was trained for another
  /// task, pipeline or feature set (learning::require_compatible).
  void set_model(std::shared_ptr<const learning::Model> model, const std::string& where = "model");
  bool has_model() const { return classification_.has_model(); }
  /// The classifier's model (null before set_model).
  const std::shared_ptr<const learning::Model>& model() const { return classification_.model(); }

  /// Runs every stage on `frame`. The result refers to internal storage valid until the next
  /// call. Without a model, candidates carry features but score 0 and head = false.
  std::span<const Candidate> process(const RgbdFrame& frame);
  /// The candidates of the last processed frame (same as process() returned).
  std::span<const Candidate> candidates() const { return state_.candidates.active(); }

  /// The cloud of the last processed frame (depth-filtered, with normals — OES: only on the
  /// pixels of its candidates; labels when present).
  const OrganizedCloud& cloud() const { return state_.cloud; }
  /// The last frame's depth noise estimate (m; NaN unless denoise.above > 0) and whether it was
  /// filtered.
  float noise_sigma() const { return state_.conditions.noise_sigma; }
  bool denoised() const { return state_.conditions.denoised; }
  /// Soil depth (m, camera z) estimated for the last frame; NaN unless range.* options need it.
  float soil_depth() const { return state_.conditions.soil_depth; }
  /// Detections (candidates classified as heads) of the last processed frame, best score first.
  std::vector<Detection> detections() const;

  StageTimer& timer() { return timer_; }
  const StageTimer& timer() const { return timer_; }

 private:
  DetectorConfig cfg_;
  steps::CloudStep cloud_;
  steps::NormalsStep normals_;
  steps::EdgesStep edges_;
  steps::ClusteringStep clustering_;
  steps::DescriptionStep description_;
  steps::ClassificationStep classification_;
  std::vector<std::unique_ptr<steps::Refiner>> refiners_;  // those the config turns on, in order
  steps::FrameState state_;
  StageTimer timer_;
};

}  // namespace cropsight::pipeline::broccoli
