#pragma once
// Semantic segmentation metrics as the grape paper reports them (Luo et al., Tables 1 and 3):
// overall accuracy (OAcc), mean per-class accuracy (mAcc) and mean intersection over union
// (mIoU), from a confusion matrix accumulated over every point of every evaluated cloud.
#include <cstdint>
#include <vector>

namespace cropsight::eval {

class ConfusionMatrix {
 public:
  explicit ConfusionMatrix(int num_classes);

  int num_classes() const { return n_; }
  /// Counts one point with ground truth `truth` predicted as `pred`; ids outside [0, n) throw.
  void add(int truth, int pred, std::int64_t count = 1);
  /// Adds two equally long label vectors.
  void add(const std::vector<int>& truth, const std::vector<int>& pred);
  void merge(const ConfusionMatrix& other);

  std::int64_t at(int truth, int pred) const { return m_[std::size_t(truth) * n_ + pred]; }
  std::int64_t total() const;
  std::int64_t truth_count(int c) const;  ///< row sum
  std::int64_t pred_count(int c) const;   ///< column sum

  /// Correct / total; NaN when empty.
  double overall_accuracy() const;
  /// Recall of class c = TP / (TP + FN); NaN when c has no ground-truth point.
  double class_accuracy(int c) const;
  /// TP / (TP + FP + FN); NaN when c is neither in the truth nor in the predictions.
  double class_iou(int c) const;
  /// Means over the classes whose value is defined (not NaN). A class absent from every
  /// evaluated cloud therefore does not pull the mean down or up.
  double mean_accuracy() const;
  double mean_iou() const;

 private:
  int n_;
  std::vector<std::int64_t> m_;
};

}  // namespace cropsight::eval
