#pragma once
// Dataset: labelled feature vectors for binary classification, stored row-major in one
// contiguous buffer so that libsvm, nanoflann and Eigen can all read it without copies.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace cropsight::learning {

struct Dataset {
  int dim = 0;                ///< feature dimension (every row has `dim` values)
  std::vector<float> values;  ///< row-major, size() * dim values
  std::vector<int> labels;    ///< 1 = positive class (e.g. broccoli head), 0 = negative

  Dataset() = default;
  explicit Dataset(int d) : dim(d) {}

  std::size_t size() const { return labels.size(); }
  bool empty() const { return labels.empty(); }
  const float* row(std::size_t i) const { return values.data() + i * std::size_t(dim); }
  std::span<const float> row_span(std::size_t i) const { return {row(i), std::size_t(dim)}; }
  /// Appends one sample; throws Error(where, ...) when x.size() != dim, x has a non-finite
  /// value or label is not 0/1. The first add() on an empty Dataset with dim 0 sets dim.
  void add(std::span<const float> x, int label, const std::string& where = "dataset");
  /// Appends all rows of `other` (same dim).
  void append(const Dataset& other, const std::string& where = "dataset");
  std::size_t positives() const;
  std::size_t negatives() const { return size() - positives(); }
  /// Rows `idx` of this dataset, in that order.
  Dataset subset(std::span<const std::size_t> idx) const;
};

}  // namespace cropsight::learning
