#include "cropsight/eval/binary_metrics.hpp"

#include <cmath>

namespace cropsight::eval {

namespace {
double ratio(std::int64_t num, std::int64_t den) { return den ? double(num) / double(den) : NAN; }
}  // namespace

double BinaryConfusion::accuracy() const { return ratio(tp + tn, total()); }
double BinaryConfusion::precision() const { return ratio(tp, tp + fp); }
double BinaryConfusion::recall() const { return ratio(tp, tp + fn); }
double BinaryConfusion::specificity() const { return ratio(tn, tn + fp); }
double BinaryConfusion::npv() const { return ratio(tn, tn + fn); }
double BinaryConfusion::f1() const { return ratio(2 * tp, 2 * tp + fp + fn); }

double BinaryConfusion::kappa() const {
  const double n = double(total());
  if (n == 0) return NAN;
  const double po = double(tp + tn) / n;
  const double pe = (double(tp + fp) * double(tp + fn) + double(tn + fn) * double(tn + fp)) / (n * n);
  if (pe >= 1.0) return po >= 1.0 ? 1.0 : NAN;
  return (po - pe) / (1.0 - pe);
}

}  // namespace cropsight::eval
