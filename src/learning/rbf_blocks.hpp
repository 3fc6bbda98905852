#pragma once
// The RBF SVM's decision sums on CPUs with AVX2 + FMA (internal header; svm_classifier.cpp picks
// it when cpu_has_avx2_fma(), the baseline build keeps its row-by-row kernel).
//
//   sum(z) = Σ_i coef_i · exp(−γ · max(0, |sv_i|² + |z|² − 2 sv_i·z))
//
// Layout: support vectors in blocks of 16, column-interleaved (block b, column j holds the 16
// values sv_{16b..16b+15}[j] side by side), so one 8-lane multiply-add advances eight dot products
// at once and no lane has to be summed across; the exponential is evaluated eight lanes at a time
// (Cephes' expf polynomial; not measured apart: the scores are tested against libsvm's to 1e-4
// relative). Several vectors are scored in one pass (sums()), two at a time, each group of blocks
// (20 KB) read once for all of them instead of once per vector (bench_learning: 5-20 % faster than
// scoring them one by one).
//
// Each vector's arithmetic does not depend on how many are scored together: sums() of one
// vector gives the bits of sums() of that vector among others (tested). Thread-safe (const).
#include <cstddef>
#include <vector>

namespace cropsight::learning::detail {

class RbfBlocks {
 public:
  static constexpr int kBlock = 16;  ///< support vectors per block
  RbfBlocks() = default;
  /// `sv`: n rows of `cols` floats (row-major; the caller's active columns only), `coef` and
  /// `norm2` (|sv_i|² over every column) per row.
  RbfBlocks(const float* sv, int n, int cols, const float* coef, const float* norm2, float gamma);

  /// True when this CPU runs the AVX2 + FMA kernel (and the build has it).
  static bool available();
  bool empty() const { return blocks_ == 0; }
  int cols() const { return cols_; }

  /// For q vectors `z` (rows of cols() floats) with |x|² in z2: out[k] = sum(z_k). Requires
  /// available(); throws Error otherwise.
  void sums(const float* z, const float* z2, std::size_t q, float* out) const;

 private:
  int cols_ = 0, blocks_ = 0;
  float gamma_ = 0.0f;
  std::vector<float> values_;        ///< blocks_ × cols_ × kBlock
  std::vector<float> coef_, norm2_;  ///< blocks_ × kBlock; padding rows have coef 0
};

}  // namespace cropsight::learning::detail
