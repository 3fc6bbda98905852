#pragma once
// Scores of seedling detections against simulator ground truth (the paper's metrics):
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

#include "cropsight/pipeline/seedling/pipeline.hpp"
#include "cropsight/pipeline/seedling/truth.hpp"

namespace cropsight::pipeline::seedling {

struct Score {
  double iou = 0;
  double sensitivity = 0;
  double volume_ratio = 0;
  bool recognised = false;  ///< iou >= 0.5
};

Score score(const FrameResult& det, const Truth& truth, const stereo::RectifiedGeometry& geometry, double cell = 0.004);

/// One pair's row of an evaluation.
struct PairResult {
  std::string pair;
  Score score;
  double ms = 0;  ///< the pipeline's total time on this pair
  int gmm_iterations = 0;
};

/// Means over the pairs; times in ms per pair (I/O excluded).
struct Figures {
  int pairs = 0;
  double recognition_rate = 0, sensitivity = 0, volume_ratio = 0;
  double ms_total = 0, ms_sgm = 0, ms_gmm = 0;
  std::vector<PairResult> per_pair;
  /// cv::ml::EM timed on the same down-sampled points as our GMM (same K, tolerance and iteration
  /// cap), and both fits' mean log-likelihoods; opencv_runs = 0 when not compared.
  int opencv_runs = 0;
  double ms_gmm_opencv = 0, gmm_mean_log_likelihood = 0, gmm_opencv_mean_log_likelihood = 0;
};

/// Accumulates pairs one at a time (for data sets on disk, in memory, or a live run).
class Evaluator {
 public:
  struct Options {
    bool compare_opencv_em = false;  ///< also fit cv::ml::EM on each detection's sampled points
    double cell = 0.004;             ///< m; top-view raster of the IoU
  };
  /// `gmm` is the pipeline's GMM config, given to cv::ml::EM when compared.
  Evaluator(const segmentation::GmmConfig& gmm, Options options);
  explicit Evaluator(const segmentation::GmmConfig& gmm) : Evaluator(gmm, Options{}) {}

  const PairResult& add(const std::string& pair, const FrameResult& det, const Truth& truth,
                        const stereo::RectifiedGeometry& geometry);
  Figures figures() const;

 private:
  segmentation::GmmConfig gmm_;
  Options opt_;
  Figures sums_;  // sums until figures() divides them
};

/// Runs `pipeline` over every pair of `data` and scores it; `progress(done)` after each pair.
Figures evaluate_seedling_dataset(const Dataset& data, const Pipeline& pipeline, const Evaluator::Options& options,
                                  const std::function<void(int)>& progress = {});

}  // namespace cropsight::pipeline::seedling
