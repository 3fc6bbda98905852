#pragma once
// Per-point features of the classical grape segmentation model (stage 5): colour,
// normal, position in the normalised ROI cloud, and at two neighbourhood radii the local
// covariance eigen-features, neighbourhood colour statistics and FPFH (PCL). Radii are in the
// neighbourhood sizes are point counts (k nearest neighbours), not radii: the dataset's clouds
// are extremely uneven in density (median nearest-neighbour spacing 0.001 unit-sphere units,
// yet 200-1800 points within 0.01), so a fixed radius gives either empty or huge neighbourhoods.
#include <cstdint>
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/threads.hpp"

namespace cropsight::pipeline::grape {

struct FeatureConfig {
  int k_small = 16;  ///< points; fine neighbourhood
  int k_large = 64;  ///< points; coarse neighbourhood
  bool fpfh = true;  ///< include the 2 × 33 FPFH bins
  int threads = 2;   ///< OpenMP threads of PCL's FPFH
  /// Points per pass (the fast recipe): 0 = features and predictions on every point, with
  /// neighbourhoods in the whole cloud (the original recipe). N > 0 = a uniform random sample
  /// of N points (every point when the cloud has fewer), neighbourhoods searched within the
  /// sample, and labels carried back to every point by nearest sample.
  int sample = 0;
  std::uint64_t sample_seed = 1;  ///< seed of the segment-time sample (fixed: deterministic labels)
  /// Carry-back (sample > 0): a point outside the sample takes the weighted vote of its
  /// carry_k nearest sample points, weight exp(-d²/d_k² - carry_colour·|rgb - rgb_s|²) (a joint
  /// bilateral upsampling guided by colour; d_k = distance to the k-th); carry_k = 1 = nearest.
  int carry_k = 4;
  double carry_colour = 200;  ///< 1/(rgb units)², colours in [0, 1]
  bool carry_soft = false;    ///< vote with the samples' class probabilities, not their labels

  template <class V>
  void visit(V& v) {
    // Ranges by the field (core/config.hpp, Range): checked by validate(), so by every preset,
    // --set and model recipe that fills this struct.
    const char* covariance = "a neighbourhood's covariance needs three points";
    v("k_small", k_small, "points; fine neighbourhood size (ours)", Range::at_least(3, covariance));
    v("k_large", k_large, "points; coarse neighbourhood size (ours)", Range::at_least(3, covariance));
    v("fpfh", fpfh, "bool; add FPFH histograms at both radii");
    v("threads", threads, "count; threads of the FPFH computation", Range::within(1, kMaxThreads));
    v("sample", sample, "points; points per pass, 0 = every point (ours)", Range::at_least(0, "0 = every point"));
    v("sample_seed", sample_seed, "1; seed of the segment-time sample (ours)");
    v("carry_k", carry_k, "count; sample points voting for each other point, 1 = nearest only (ours)",
      Range::at_least(1));
    v("carry_colour", carry_colour, "1/rgb^2; colour weight of the carry-back vote (ours)", Range::at_least(0));
    v("carry_soft", carry_soft, "bool; carry-back votes with class probabilities (ours)");
  }
  /// "k_small=16;k_large=64;fpfh=1" (+ ";sample=N;sample_seed=S;carry_k=K;carry_colour=C;carry_soft=B"
  /// when sample > 0): stored inside model files, so a model is applied the way it was trained.
  /// Recipes without the sample keys (every model written before them) mean sample = 0.
  std::string recipe() const;
  /// Parses recipe() text with the fields' own parsers and ranges (visit()): a malformed or
  /// out-of-range value, an item that is not key=value, a repeated, unknown or missing key
  /// (k_small, k_large and fpfh are required) throws Error(where, "feature recipe: 'KEY' ...").
  /// `where` names the model file.
  static FeatureConfig from_recipe(const std::string& text, const std::string& where);
  /// Throws Error(where, "'PREFIXk_small' must be at least 3 (...), got 1") for the first field
  /// out of its range declared in visit() (check_config). `prefix` is the fields' key path
  /// ("features.").
  void validate(const std::string& where, const std::string& prefix = "") const;
};

/// Number of features per point for `cfg`.
std::size_t grape_feature_count(const FeatureConfig& cfg);
/// Feature names, in column order (for documentation and importance dumps).
std::vector<std::string> grape_feature_names(const FeatureConfig& cfg);

/// Row-major features (rows = subset.size(), or every point when `subset` is empty). Needs
/// normals and colours in `cloud`; neighbourhoods use the whole cloud. Throws Error otherwise.
std::vector<float> grape_point_features(const Cloud& cloud, const FeatureConfig& cfg,
                                        const std::vector<int>& subset = {});

/// The pass sample of a cloud of `size` points: cfg.sample indices drawn uniformly without
/// replacement (std::mt19937_64 seeded by `seed`), sorted ascending; every index when
/// cfg.sample is 0 or not below `size`. Same seed, same sample.
std::vector<int> grape_sample(std::size_t size, const FeatureConfig& cfg, std::uint64_t seed);

/// Features of the points `sample` of `cloud` computed as if the cloud were only those points
/// (neighbourhoods, centroid searched within the sample): rows in the order of `sample`. This
/// is what the fast recipe trains and predicts on. Throws Error as grape_point_features.
std::vector<float> grape_sample_features(const Cloud& cloud, const FeatureConfig& cfg, const std::vector<int>& sample);

}  // namespace cropsight::pipeline::grape
