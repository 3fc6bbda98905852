#include "cropsight/eval/segmentation_metrics.hpp"

#include <limits>
#include <string>

#include "cropsight/core/error.hpp"

namespace cropsight::eval {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

ConfusionMatrix::ConfusionMatrix(int num_classes) : n_(num_classes) {
  if (num_classes <= 0) throw Error("confusion matrix", "number of classes must be positive");
  m_.assign(std::size_t(n_) * n_, 0);
}

void ConfusionMatrix::add(int truth, int pred, std::int64_t count) {
  if (truth < 0 || truth >= n_ || pred < 0 || pred >= n_)
    throw Error("confusion matrix", "label out of range [0, " + std::to_string(n_) + "): truth " +
                                        std::to_string(truth) + ", prediction " + std::to_string(pred));
  m_[std::size_t(truth) * n_ + pred] += count;
}

void ConfusionMatrix::add(const std::vector<int>& truth, const std::vector<int>& pred) {
  if (truth.size() != pred.size()) throw Error("confusion matrix", "truth and prediction differ in length");
  for (std::size_t i = 0; i < truth.size(); ++i) add(truth[i], pred[i]);
}

void ConfusionMatrix::merge(const ConfusionMatrix& other) {
  if (other.n_ != n_) throw Error("confusion matrix", "cannot merge matrices of different sizes");
  for (std::size_t i = 0; i < m_.size(); ++i) m_[i] += other.m_[i];
}

std::int64_t ConfusionMatrix::total() const {
  std::int64_t s = 0;
  for (auto v : m_) s += v;
  return s;
}

std::int64_t ConfusionMatrix::truth_count(int c) const {
  std::int64_t s = 0;
  for (int j = 0; j < n_; ++j) s += at(c, j);
  return s;
}

std::int64_t ConfusionMatrix::pred_count(int c) const {
  std::int64_t s = 0;
  for (int i = 0; i < n_; ++i) s += at(i, c);
  return s;
}

double ConfusionMatrix::overall_accuracy() const {
  const std::int64_t t = total();
  if (t == 0) return kNaN;
  std::int64_t correct = 0;
  for (int c = 0; c < n_; ++c) correct += at(c, c);
  return double(correct) / double(t);
}

double ConfusionMatrix::class_accuracy(int c) const {
  const std::int64_t t = truth_count(c);
  return t == 0 ? kNaN : double(at(c, c)) / double(t);
}

double ConfusionMatrix::class_iou(int c) const {
  const std::int64_t uni = truth_count(c) + pred_count(c) - at(c, c);
  return uni == 0 ? kNaN : double(at(c, c)) / double(uni);
}

double ConfusionMatrix::mean_accuracy() const {
  double s = 0;
  int k = 0;
  for (int c = 0; c < n_; ++c)
    if (double a = class_accuracy(c); a == a) s += a, ++k;
  return k ? s / k : kNaN;
}

double ConfusionMatrix::mean_iou() const {
  double s = 0;
  int k = 0;
  for (int c = 0; c < n_; ++c)
    if (double a = class_iou(c); a == a) s += a, ++k;
  return k ? s / k : kNaN;
}

}  // namespace cropsight::eval
