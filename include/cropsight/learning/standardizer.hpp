#pragma once
// Feature standardisation z = (x - mean) / std, fitted on training data and stored with the
// model so that detection applies exactly the training-time transform.
#include <span>
#include <vector>

#include "cropsight/learning/dataset.hpp"

namespace cropsight::learning {

struct Standardizer {
  std::vector<float> mean;  ///< per feature
  std::vector<float> std;   ///< per feature; constant features get 1 (so they map to 0)

  int dim() const { return int(mean.size()); }
  /// Population mean and standard deviation of every column of `data`.
  static Standardizer fit(const Dataset& data);
  /// out[i] = (x[i] - mean[i]) / std[i]; `out` must hold dim() values.
  void apply(const float* x, float* out) const;
  /// Returns a standardised copy of `data`.
  Dataset apply(const Dataset& data) const;
};

}  // namespace cropsight::learning
