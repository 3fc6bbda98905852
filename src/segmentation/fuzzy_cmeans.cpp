#include "cropsight/segmentation/fuzzy_cmeans.hpp"

#include <algorithm>
#include <cmath>

#include "cropsight/core/error.hpp"
#include "kmeans_seed.hpp"

namespace cropsight::segmentation {

FuzzyClustering fuzzy_cmeans(const std::vector<Eigen::Vector3f>& points, const FuzzyCMeansConfig& cfg,
                             const std::string& where) {
  if (cfg.clusters < 1) throw Error(where, "clusters must be >= 1");
  if (!(cfg.fuzziness > 1.0)) throw Error(where, "fuzziness must be > 1");
  if (int(points.size()) < cfg.clusters) throw Error(where, "fewer points than clusters");
  const int n = int(points.size()), c = cfg.clusters;
  const double expo = 1.0 / (cfg.fuzziness - 1.0);  // u ∝ (1/d^2)^(1/(m-1))
  FuzzyClustering r;
  r.centres = kmeanspp_seeds(points, c, cfg.seed);
  r.memberships.assign(std::size_t(n) * c, 0.0f);
  std::vector<double> w(c);
  for (r.iterations = 1; r.iterations <= cfg.max_iterations; ++r.iterations) {
    double change = 0;
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d p = points[i].cast<double>();
      double total = 0;
      int exact = -1;
      for (int j = 0; j < c; ++j) {
        const double d2 = (p - r.centres[j]).squaredNorm();
        if (d2 < 1e-20) exact = j;
        w[j] = std::pow(1.0 / std::max(d2, 1e-20), expo);
        total += w[j];
      }
      for (int j = 0; j < c; ++j) {
        const double u = exact >= 0 ? double(j == exact) : w[j] / total;
        float& m = r.memberships[std::size_t(i) * c + j];
        change = std::max(change, std::fabs(u - double(m)));
        m = float(u);
      }
    }
    for (int j = 0; j < c; ++j) {
      Eigen::Vector3d s = Eigen::Vector3d::Zero();
      double ws = 0;
      for (int i = 0; i < n; ++i) {
        const double um = std::pow(double(r.memberships[std::size_t(i) * c + j]), cfg.fuzziness);
        s += um * points[i].cast<double>();
        ws += um;
      }
      if (ws > 0) r.centres[j] = s / ws;
    }
    if (change <= cfg.tolerance) break;
  }
  r.iterations = std::min(r.iterations, cfg.max_iterations);
  r.labels.assign(n, 0);
  for (int i = 0; i < n; ++i) {
    const float* u = &r.memberships[std::size_t(i) * c];
    r.labels[i] = int(std::max_element(u, u + c) - u);
  }
  return r;
}

}  // namespace cropsight::segmentation
