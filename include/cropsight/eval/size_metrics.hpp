#pragma once
// Size-estimation metrics (Kusumam et al. §6.3, Table 4 / Fig. 15): errors e_i = estimate_i −
// truth_i of head diameters, in millimetres.
//
//   mede_mm    median error, median(e)  (signed: negative = the estimator underestimates)
//   mad_mm     median absolute deviation of the errors, median(|e_i − median(e)|)  (spread)
//   medae_mm   median absolute error, median(|e_i|)  (reported too: MAD ignores a constant bias)
//   pearson_r  Pearson correlation of estimates and truths (NaN when either has no spread)
//   rmse_mm    root mean square error
// The median of an even count is the mean of the two middle values. With no pairs every figure
// is NaN and n = 0.
#include <vector>

#include "cropsight/core/statistics.hpp"  // median

namespace cropsight::eval {

struct SizeMetrics {
  int n = 0;
  double mede_mm = 0.0, mad_mm = 0.0, medae_mm = 0.0, pearson_r = 0.0, rmse_mm = 0.0;
};

/// Throws Error("size metrics", ...) when the two vectors differ in length or hold a non-finite
/// value.
SizeMetrics size_metrics(const std::vector<double>& estimate_mm, const std::vector<double>& truth_mm);

double pearson_r(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace cropsight::eval
