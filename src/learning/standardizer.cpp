#include "cropsight/learning/standardizer.hpp"

#include <cmath>

namespace cropsight::learning {

Standardizer Standardizer::fit(const Dataset& data) {
  const std::size_t d = std::size_t(data.dim), n = data.size();
  // Accumulate in double: features such as VFH bins are small and many samples are summed.
  std::vector<double> sum(d, 0.0), sq(d, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const float* x = data.row(i);
    for (std::size_t j = 0; j < d; ++j) sum[j] += x[j];
  }
  Standardizer s;
  s.mean.resize(d);
  s.std.resize(d);
  for (std::size_t j = 0; j < d; ++j) s.mean[j] = n ? float(sum[j] / double(n)) : 0.0f;
  for (std::size_t i = 0; i < n; ++i) {
    const float* x = data.row(i);
    for (std::size_t j = 0; j < d; ++j) {
      const double c = double(x[j]) - double(s.mean[j]);
      sq[j] += c * c;
    }
  }
  for (std::size_t j = 0; j < d; ++j) {
    const double sd = n ? std::sqrt(sq[j] / double(n)) : 0.0;
    // A constant feature carries no information; std 1 maps it to 0 instead of dividing by 0.
    s.std[j] = sd > 1e-12 ? float(sd) : 1.0f;
  }
  return s;
}

void Standardizer::apply(const float* x, float* out) const {
  const std::size_t d = mean.size();
  for (std::size_t j = 0; j < d; ++j) out[j] = (x[j] - mean[j]) / std[j];
}

Dataset Standardizer::apply(const Dataset& data) const {
  Dataset out(data.dim);
  out.labels = data.labels;
  out.values.resize(data.values.size());
  for (std::size_t i = 0; i < data.size(); ++i) apply(data.row(i), out.values.data() + i * std::size_t(data.dim));
  return out;
}

}  // namespace cropsight::learning
