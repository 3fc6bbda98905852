#pragma once
// k-fold stratified cross-validated grid search over the SVM cost C and RBF γ on log2 grids,
// like libsvm's tools/grid.py (default grids log2 C = -5:2:15, log2 γ = 3:-2:-15). The
// standardiser is refitted on each training fold so that no statistic of the held-out fold
// leaks into its model.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "cropsight/learning/classifier.hpp"
#include "cropsight/learning/dataset.hpp"

namespace cropsight::learning {

struct GridSearchConfig {
  int folds = 5;                                     ///< stratified folds (paper: 5-fold cross-validation)
  std::vector<double> log2_c{-5.0, 15.0, 2.0};       ///< begin, end, step (grid.py default)
  std::vector<double> log2_gamma{3.0, -15.0, -2.0};  ///< begin, end, step (grid.py default; RBF only)
  std::string metric = "accuracy";                   ///< accuracy (grid.py) | kappa (better for unbalanced classes)
  int seed = 1;                                      ///< fold assignment shuffle seed

  template <class V>
  void visit(V& v) {
    v("folds", folds, "cross-validation folds, stratified (paper: 5)");
    v("log2_c", log2_c, "log2 C grid [begin, end, step] (libsvm grid.py default [-5, 15, 2])");
    v("log2_gamma", log2_gamma, "log2 gamma grid [begin, end, step] (grid.py default [3, -15, -2]); RBF only");
    v("metric", metric, "accuracy | kappa: cross-validated score maximised");
    v("seed", seed, "fold shuffle seed");
  }
  void validate(const std::string& where) const;
};

struct GridPoint {
  double c = 0, gamma = 0;         ///< gamma 0 for the linear SVM
  double accuracy = 0, kappa = 0;  ///< pooled over the held-out folds
};

struct GridSearchResult {
  std::vector<GridPoint> points;  ///< every evaluated (C, γ), in grid order
  GridPoint best;                 ///< highest metric; ties go to the first in grid order
  ClassifierParams params;        ///< the input params with the best C (and γ) filled in
};

/// Stratified fold index (0..folds-1) of every sample; deterministic for a seed.
std::vector<int> stratified_folds(const std::vector<int>& labels, int folds, int seed);

/// Cross-validated predictions (0/1) of `params` on raw (unstandardised) `data`.
std::vector<int> cross_validate(const Dataset& data, const ClassifierParams& params, const std::vector<int>& fold_of,
                                int folds);

/// Called after each grid point with (points done, points in the grid), e.g. for a progress line.
using GridProgress = std::function<void(std::size_t, std::size_t)>;

/// Runs the grid search for params.type svm-rbf (C × γ) or svm-linear (C only); throws
/// Error(where, ...) for knn, an empty grid or a class with fewer samples than folds.
GridSearchResult grid_search(const Dataset& data, const ClassifierParams& params, const GridSearchConfig& cfg,
                             const std::string& where = "grid search", const GridProgress& progress = {});

}  // namespace cropsight::learning
