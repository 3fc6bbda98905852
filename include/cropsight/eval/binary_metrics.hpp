#pragma once
// Binary classification metrics from a 2×2 confusion matrix, as Table I of Montes et al. 2020
// ("Real-time detection of broccoli crops in 3D point clouds") reports them per cluster.
//
//   accuracy    (TP + TN) / N
//   precision   TP / (TP + FP)          (positive predictive value)
//   recall      TP / (TP + FN)          (sensitivity, true-positive rate)
//   specificity TN / (TN + FP)          (true-negative rate)
//   npv         TN / (TN + FN)          (negative predictive value)
//   f1          2·TP / (2·TP + FP + FN)
//   kappa       Cohen's κ = (p_o − p_e) / (1 − p_e), p_o = accuracy,
//               p_e = [(TP+FP)(TP+FN) + (TN+FN)(TN+FP)] / N²  (chance agreement)
//
// A ratio whose denominator is 0 is NaN (undefined, e.g. precision with no positive
// prediction); κ is 1 when p_e = 1 and the agreement is perfect, NaN when p_e = 1 otherwise.
#include <cstdint>

namespace cropsight::eval {

struct BinaryConfusion {
  std::int64_t tp = 0, fp = 0, tn = 0, fn = 0;

  void add(bool truth, bool predicted) { (truth ? (predicted ? tp : fn) : (predicted ? fp : tn)) += 1; }
  void merge(const BinaryConfusion& o) {
    tp += o.tp;
    fp += o.fp;
    tn += o.tn;
    fn += o.fn;
  }
  std::int64_t total() const { return tp + fp + tn + fn; }
  std::int64_t positives() const { return tp + fn; }  ///< ground-truth positives

  double accuracy() const;
  double precision() const;
  double recall() const;
  double specificity() const;
  double npv() const;
  double f1() const;
  double kappa() const;
};

}  // namespace cropsight::eval
