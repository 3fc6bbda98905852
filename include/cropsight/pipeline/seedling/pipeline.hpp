#pragma once
// Broccoli-seedling recognition from a rectified stereo pair (after "A method for
// broccoli seedling recognition in natural environment based on binocular stereo vision and
// Gaussian mixture model"):
//
//   disparity (SGBM + LR check + hole filling) → 3D points (invalid removed) → soil plane
//   (RANSAC) → points above the soil → non-uniform grid down-sampling to exactly 4096 points →
//   GMM (EM, K = 10) → recognition rule → KNN outlier filter → dense seedling points, top-view
//   mask, envelope box, per-stage timings.
//
// Pipeline composes these steps from one Config (one preset); each step after the
// reconstruction is a function of seedling/steps.hpp. No metric, ground truth or file I/O here:
// the evaluator is seedling/eval.hpp, the data-set reader seedling/truth.hpp.
//
// Recognition rule (why: transplanted seedlings stand clearly above the soil and above the low
// weeds around them, and form one connected plant):
//   1. Only points higher than `min_height` above the fitted soil plane enter the GMM (the soil
//      itself would otherwise take most components; this is our change to the paper's order).
//      With candidate_open > 0 the left-image mask of these candidates is first opened (ellipse
//      of that radius), which drops soil pixels raised by disparity errors (they are scattered).
//      With candidate_min_exg > -1, candidates whose left-image colour is not green enough
//      (excess-green index below it) are dropped first: the soil pixels next to a leaf edge that
//      the matching window gave the leaf's disparity lie outside the leaf in 3D and stretch the
//      envelope box (foreground fattening).
//   2. The seed component is the one whose member points have the largest mean height (among
//      components with at least `min_component_points` points).
//   3. Components are added while one of them has a mean height >= `height_ratio` x the seed's
//      and a member point within `join_distance` of the points chosen so far (the lower leaves
//      of the same plant touch the upper ones; distant weeds do not), measured seen from above
//      with `join_top_view` (the default): the leaves meet at the stem, whose thin petioles often
//      lie below min_height or get no disparity, so in 3D an upper leaf can float > 1.5 cm above
//      the others while from above it still touches them.
//   4. The chosen points go through the KNN outlier filter (mean distance to k neighbours above
//      mean + alpha sigma removed).
//   5. Dense result: every reconstructed point above `min_height` whose top-view cell lies
//      within `topview_dilate` cells of a kept sampled point, restricted to the largest connected
//      top-view region (one plant is one connected region seen from above).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "cropsight/core/image.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/measure/envelope.hpp"
#include "cropsight/pipeline/seedling/config.hpp"
#include "cropsight/pipeline/seedling/frame_result.hpp"
#include "cropsight/pipeline/seedling/top_view.hpp"
#include "cropsight/segmentation/gmm.hpp"
#include "cropsight/stereo/rectification.hpp"

namespace cropsight::pipeline::seedling {

/// The broccoli-seedling recogniser. Construct once from a config (validated here: Error naming
/// the key), then process() each rectified pair. process() is const and keeps no state between
/// pairs, so one instance may serve several threads.
class Pipeline {
 public:
  explicit Pipeline(Config config, const std::string& where = "seedling config");
  /// The pipeline of `preset` (load_config).
  static Pipeline from_preset(const std::string& preset = "seedling");

  /// Detects the seedling in a rectified pair with the given rectified geometry. Throws
  /// Error(where, ...) for a left image whose size differs from the geometry or a right image
  /// whose size differs from the left one.
  FrameResult process(const ColorImage& left, const ColorImage& right, const stereo::RectifiedGeometry& geometry,
                      const std::string& where = "stereo pair") const;

  const Config& config() const { return cfg_; }
  /// Nothing carries over between pairs; here so that every crop's pipeline has the same entry points.
  void reset() {}

 private:
  Config cfg_;
};

}  // namespace cropsight::pipeline::seedling
