#pragma once
// The classical grape segmentation model: per-point features (grape/features.hpp) classified by
// gradient-boosted trees (learning::Gbdt). The feature recipe is stored inside the model file,
// so a model segments a cloud with exactly the features it was trained on.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"
#include "cropsight/learning/gbdt.hpp"
#include "cropsight/pipeline/grape/features.hpp"

namespace cropsight::pipeline::grape {

struct GbdtConfig {
  FeatureConfig features;
  learning::GbdtParams gbdt;
  int points_per_cloud = 4000;      ///< training rows drawn per cloud (rare classes kept whole)
  int rare_class_max = 400;         ///< classes with fewer points than this in a cloud are kept whole
  double class_weight_power = 0.5;  ///< row weight = (median class share / class share)^power
  int sample_draws = 4;             ///< fast recipe (features.sample > 0): pass samples drawn per cloud
  std::uint64_t seed = 1;

  template <class V>
  void visit(V& v) {
    v("features", features, "per-point feature recipe");
    v("gbdt", gbdt, "XGBoost parameters");
    v("points_per_cloud", points_per_cloud, "count; training rows sampled per cloud (ours)", Range::at_least(1));
    v("rare_class_max", rare_class_max, "count; classes smaller than this in a cloud are kept whole (ours)",
      Range::at_least(0));
    v("class_weight_power", class_weight_power, "1; inverse-frequency class weight exponent (ours)",
      Range::at_least(0));
    v("sample_draws", sample_draws,
      "count; fast recipe only: pass samples per training cloud, each featurised as at segment time (ours)",
      Range::at_least(1));
    v("seed", seed, "1; sampling seed");
  }

  /// Throws Error(where, "'gbdt.rounds' must be at least 1, got 0") for the first field out of
  /// range, the nested features and gbdt fields included (the ranges declared in visit(), and
  /// learning::GbdtParams::validate): checked before any work, so that a bad value is named as
  /// the user wrote it rather than failing deep in XGBoost.
  void validate(const std::string& where) const;
};

/// Trains on the labelled `clouds` (labels 0..gbdt.num_class-1). `log` (optional) receives
/// progress lines.
learning::Gbdt train_grape_gbdt(const std::vector<Cloud>& clouds, const GbdtConfig& cfg,
                                const std::function<void(const std::string&)>& log = {});

/// The fast recipe's carry-back: points of `sample` keep `sample_labels`; every other point
/// takes the vote of its fc.carry_k nearest sample points, weight exp(-d²/d_k² -
/// fc.carry_colour·|rgb - rgb_s|²) (carry_k = 1, or no colours: the nearest sample's label).
/// Labels in [0, num_class). With `sample_proba` (sample × num_class, row-major) each voter
/// adds weight × its class probabilities instead of weight to its label. Every point gets a label.
/// `scores_out` (optional) receives per point (row-major, cloud size × num_class) the vote
/// normalised to sum 1: a sample point's own probabilities (or one-hot label), another point's
/// weighted vote (one-hot of the nearest sample when it alone decides); for soft votes over passes.
std::vector<int> grape_carry_back(const Cloud& cloud, const std::vector<int>& sample,
                                  const std::vector<int>& sample_labels, const FeatureConfig& fc, int num_class,
                                  int threads = 2, const std::vector<float>* sample_proba = nullptr,
                                  std::vector<float>* scores_out = nullptr);

/// Labels of every point of `cloud` (needs normals and colours). With a fast-recipe model
/// (recipe sample = N > 0) the model classifies a fixed-seed sample of N points and every other
/// point takes the label of its nearest sample point. `scores` (optional) receives per point the
/// class probabilities (cloud size × classes, row-major; carried-back votes for a fast recipe).
std::vector<int> segment_grape_gbdt(const learning::Gbdt& model, const Cloud& cloud, int threads = 2,
                                    std::vector<float>* scores = nullptr);

}  // namespace cropsight::pipeline::grape
