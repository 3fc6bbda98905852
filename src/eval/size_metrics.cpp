#include "cropsight/eval/size_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cropsight/core/error.hpp"

namespace cropsight::eval {

double pearson_r(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  if (n < 2) return std::numeric_limits<double>::quiet_NaN();
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
  ma /= double(n), mb /= double(n);
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  if (!(saa > 0) || !(sbb > 0)) return std::numeric_limits<double>::quiet_NaN();
  return sab / std::sqrt(saa * sbb);
}

SizeMetrics size_metrics(const std::vector<double>& est, const std::vector<double>& truth) {
  if (est.size() != truth.size()) throw Error("size metrics", "estimates and truths differ in count");
  SizeMetrics m;
  m.n = int(est.size());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (est.empty()) {
    m.mede_mm = m.mad_mm = m.medae_mm = m.pearson_r = m.rmse_mm = nan;
    return m;
  }
  std::vector<double> e(est.size()), ae(est.size());
  double sq = 0;
  for (std::size_t i = 0; i < est.size(); ++i) {
    if (!std::isfinite(est[i]) || !std::isfinite(truth[i])) throw Error("size metrics", "non-finite diameter");
    e[i] = est[i] - truth[i];
    ae[i] = std::abs(e[i]);
    sq += e[i] * e[i];
  }
  m.mede_mm = median(e);
  std::vector<double> dev(e.size());
  for (std::size_t i = 0; i < e.size(); ++i) dev[i] = std::abs(e[i] - m.mede_mm);
  m.mad_mm = median(dev);
  m.medae_mm = median(ae);
  m.rmse_mm = std::sqrt(sq / double(e.size()));
  m.pearson_r = pearson_r(est, truth);
  return m;
}

}  // namespace cropsight::eval
