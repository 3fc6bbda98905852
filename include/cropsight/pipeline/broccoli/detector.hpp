#pragma once
// Detector: the broccoli head pipelines of Montes et al. 2020 composed from the stage
// modules, one frame at a time:
//
//   depth image → [denoise.above > 0: a frame noisier than that is bilateral-filtered]
//     → organised cloud (metres, camera frame) → depth-range filter
//     → integral-image normals
//     → OES: organised edges + flood fill bounded by edges
//       ORG: flood fill on normal angle, grown from low-curvature points
//       FEC: [statistical outlier removal] + Euclidean clustering (k-d tree)
//     → features per cluster (VFH [, viewpoint angle, geometric, CVFH])
//     → classifier score (SVM decision value / KNN vote)
//     → [detection.split_concave_angle_deg > 0: rejected clusters split at concave creases, pieces classified]
//     → [detection.grow_tolerance > 0: head masks grown over unclustered debris]
//     → [cnn.model: heads the depth CNN finds where no accepted head lies] → detections
//
// Every stage is timed (StageTimer, names: "cloud", "normals", "edges", "outliers",
// "clustering", "features", "classify", "split", "completion", "cnn"; "denoise", the noise estimate and filter, is
// timed inside "cloud"). OES needs no normals to segment (unless crease edges
// are on): it computes them after the flood fill, only for the pixels of the kept segments (the
// only ones the features read), so its cloud() has NaN normals elsewhere. All buffers (cloud, normals' integral images,
// edge labels, flood-fill stacks, feature vectors, candidate list) live in the detector and are reused from frame to
// frame: after the first frame of a given size, the stages allocate only what the segmentation functions return (the
// segments' index lists).
//
// Not thread-safe: one detector per thread.
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "cropsight/core/detection.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/core/segment.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/learning/model.hpp"
#include "cropsight/pipeline/broccoli/detector_config.hpp"
#include "cropsight/segmentation/flood_fill.hpp"
#include "cropsight/segmentation/segment_growth.hpp"
#include "cropsight/segmentation/segment_split.hpp"

namespace cropsight::nn {
class CenterNetOnnx;
}

namespace cropsight::pipeline::broccoli {

/// Task name recorded in model files.
inline constexpr const char* kBroccoliTask = "broccoli-heads";

/// One cluster of one frame.
struct Candidate {
  Segment segment;              ///< pixel indices (ascending) + centroid (m, camera) + boxes
  std::vector<float> features;  ///< concatenated features (FeatureSet order)
  float score = 0.0f;           ///< classifier score (0 when no model)
  bool head = false;            ///< score > threshold + margin
  int normal_points = -1;       ///< points of the segment with a normal (-1: not counted, min_normal_points 0)
  bool described = true;        ///< normal_points >= detection.min_normal_points (else never a head)
  bool oversized = false;       ///< over detection.split_oversized_above: not described, only split
  bool proposed = false;        ///< a head proposed by the depth CNN (cnn.model): no features, not classified
};

class Detector {
 public:
  /// Validates the config; throws Error("config", ...) when it is invalid.
  explicit Detector(DetectorConfig cfg);
  ~Detector();
  Detector(const Detector&) = delete;
  Detector& operator=(const Detector&) = delete;

  const DetectorConfig& config() const { return cfg_; }
  std::size_t feature_dimension() const;

  /// Uses `model` to score clusters. Throws Error(where, ...) when it was trained for another
  /// task, pipeline or feature set (learning::require_compatible).
  void set_model(std::shared_ptr<const learning::Model> model, const std::string& where = "model");
  bool has_model() const { return model_ != nullptr; }
  /// The classifier's model (null before set_model).
  const std::shared_ptr<const learning::Model>& model() const { return model_; }

  /// Runs every stage on `frame`. The result refers to internal storage valid until the next
  /// call. Without a model, candidates carry features but score 0 and head = false.
  std::span<const Candidate> process(const RgbdFrame& frame);
  /// The candidates of the last processed frame (same as process() returned).
  std::span<const Candidate> candidates() const { return {candidates_.data(), count_}; }

  /// The cloud of the last processed frame (depth-filtered, with normals — OES: only on the
  /// pixels of its candidates; labels when present).
  const OrganizedCloud& cloud() const { return cloud_; }
  /// The last frame's depth noise estimate (m; NaN unless denoise.above > 0) and whether it was
  /// filtered.
  float noise_sigma() const { return noise_sigma_; }
  bool denoised() const { return denoised_frame_; }
  /// Soil depth (m, camera z) estimated for the last frame; NaN unless range.* options need it.
  float soil_depth() const { return soil_depth_; }
  /// Detections (candidates classified as heads) of the last processed frame, best score first.
  std::vector<Detection> detections() const;

  StageTimer& timer() { return timer_; }
  const StageTimer& timer() const { return timer_; }

 private:
  void make_cloud(const RgbdFrame& frame);  // deprojection + depth-range filter
  void normals(std::span<const int> select = {});
  void cluster();  // normals (all pixels, or only the kept OES segments' pixels) + edges + clustering
  void cluster_oes();
  void segment_debris();  // oes.debris_tolerance > 0: second OES pass over what the first did not keep
  void cluster_org();
  void cluster_fec();
  void describe(Candidate& c);  // features (+ the normal count when min_normal_points asks for it)
  void classify(Candidate& c, float threshold);
  // classify() of every candidate in `cands`, the described ones scored together
  // (learning::Model::score_rows: the same scores, the support vectors read once per block).
  void classify_all(std::span<Candidate* const> cands, float threshold);
  float head_threshold() const;
  void split_at_creases();  // detection.split_concave_angle_deg > 0: rejected (and with split_accepted, accepted)
                            // clusters split at concave creases
  void complete_heads();    // detection.grow_tolerance > 0: head masks grow over unclustered debris
  void add_cnn_heads(const RgbdFrame& frame);  // cnn.model: the CNN's heads that no accepted head overlaps

  DetectorConfig cfg_;
  features::FeatureSet feature_set_;
  std::shared_ptr<const learning::Model> model_;
  std::unique_ptr<nn::CenterNetOnnx> cnn_;  // cnn.model loaded; null when off
  std::vector<int> cnn_rest_;               // add_cnn_heads: a rejected cluster less a proposal's pixels
  StageTimer timer_;

  // Workspaces reused across frames.
  OrganizedCloud cloud_;
  std::vector<float> ray_x_, ray_y_;  // per pixel (u - cx)/fx, (v - cy)/fy for the current camera
  CameraIntrinsics ray_camera_;
  std::unique_ptr<geometry::IntegralNormalEstimator> normals_;
  std::vector<std::uint8_t> edges_;
  segmentation::OrganizedClusteringWorkspace flood_;
  std::vector<Segment> segments_;
  std::vector<int> valid_;
  std::vector<Candidate> candidates_;  // a pool: only grows, so its buffers are reused
  std::size_t count_ = 0;              // candidates of the last frame
  std::vector<float> scratch_;
  std::vector<Candidate*> batch_, batch_input_;  // classify_all: the scored ones; its input
  std::vector<float> batch_rows_, batch_scores_;
  float soil_depth_ = std::numeric_limits<float>::quiet_NaN();
  segmentation::OesConfig oes_frame_;  // cfg_.oes, scaled to the frame's range when range.reference_range > 0
  std::vector<std::uint32_t> depth_histogram_;
  segmentation::SegmentGrowthWorkspace growth_;
  std::vector<Segment*> segment_ptrs_;
  std::vector<int> grow_order_;
  std::vector<std::uint8_t> debris_edges_;
  std::vector<int> kept_labels_;
  std::vector<int> split_targets_;
  std::vector<std::uint8_t> crease_marks_;
  segmentation::SegmentSplitWorkspace split_ws_;
  std::vector<Candidate> pieces_;
  float noise_sigma_ = std::numeric_limits<float>::quiet_NaN();
  bool denoised_frame_ = false;
  std::vector<std::uint32_t> noise_bins_;
  std::vector<std::uint16_t> denoised_;
  std::vector<char> split_replace_;  // per candidate: kept, replaced by its pieces, slot taken
  std::vector<char> split_scored_;   // per piece: described and classified
};

}  // namespace cropsight::pipeline::broccoli
