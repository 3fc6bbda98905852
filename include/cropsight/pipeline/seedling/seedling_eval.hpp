#pragma once
// Scores of seedling detections against simulator ground truth (issue 5's metrics):
//   top-view IoU and sensitivity (intersection / true area) on the TRUE soil plane, both masks
//   rasterised on one grid (cell 4 mm, 3x3 closing); the true top view is the seedling as the left
//   camera sees it (ground-truth disparity at the ground-truth mask's pixels);
//   volume ratio = detected / true envelope-box volume (true box from the seedling mesh);
//   recognition rate = share of pairs with IoU >= 0.5.
// The evaluator joins truth to detections and returns figures; the CLI (eval seedling) only
// formats them.
#include <functional>
#include <string>
#include <vector>

#include "cropsight/pipeline/seedling/seedling_pipeline.hpp"
#include "cropsight/pipeline/seedling/seedling_truth.hpp"

namespace cropsight::pipeline {

struct SeedlingScore {
  double iou = 0;
  double sensitivity = 0;
  double volume_ratio = 0;
  bool recognised = false;  ///< iou >= 0.5
};

SeedlingScore score_seedling(const SeedlingDetection& det, const SeedlingTruth& truth,
                             const stereo::RectifiedGeometry& geometry, double cell = 0.004);

/// One pair's row of an evaluation.
struct SeedlingPairResult {
  std::string pair;
  SeedlingScore score;
  double ms = 0;  ///< the pipeline's total time on this pair
  int gmm_iterations = 0;
};

/// Means over the pairs; times in ms per pair (I/O excluded).
struct SeedlingEvaluation {
  int pairs = 0;
  double recognition_rate = 0, sensitivity = 0, volume_ratio = 0;
  double ms_total = 0, ms_sgm = 0, ms_gmm = 0;
  std::vector<SeedlingPairResult> per_pair;
  /// cv::ml::EM timed on the same down-sampled points as our GMM (same K, tolerance and iteration
  /// cap), and both fits' mean log-likelihoods; opencv_runs = 0 when not compared.
  int opencv_runs = 0;
  double ms_gmm_opencv = 0, gmm_mean_log_likelihood = 0, gmm_opencv_mean_log_likelihood = 0;
};

/// Accumulates pairs one at a time (for data sets on disk, in memory, or a live run).
class SeedlingEvaluator {
 public:
  struct Options {
    bool compare_opencv_em = false;  ///< also fit cv::ml::EM on each detection's sampled points
    double cell = 0.004;             ///< m; top-view raster of the IoU
  };
  /// `gmm` is the pipeline's GMM config, given to cv::ml::EM when compared.
  SeedlingEvaluator(const segmentation::GmmConfig& gmm, Options options);
  explicit SeedlingEvaluator(const segmentation::GmmConfig& gmm) : SeedlingEvaluator(gmm, Options{}) {}

  const SeedlingPairResult& add(const std::string& pair, const SeedlingDetection& det, const SeedlingTruth& truth,
                                const stereo::RectifiedGeometry& geometry);
  SeedlingEvaluation result() const;

 private:
  segmentation::GmmConfig gmm_;
  Options opt_;
  SeedlingEvaluation sums_;  // sums until result() divides them
};

/// Runs `pipeline` over every pair of `data` and scores it; `progress(done)` after each pair.
SeedlingEvaluation evaluate_seedling_dataset(const SeedlingDataset& data, const SeedlingPipeline& pipeline,
                                             const SeedlingEvaluator::Options& options,
                                             const std::function<void(int)>& progress = {});

}  // namespace cropsight::pipeline
