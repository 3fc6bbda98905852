#include "cropsight/segmentation/gmm.hpp"

// The EM itself lives in gmm_em.hpp, compiled here for the x86-64 baseline and in gmm_avx2.cpp
// for AVX2 + FMA; fit_gmm() checks its input and picks the variant the CPU runs.
#include "gmm_em_deps.hpp"

#define CROPSIGHT_EM_NS em_portable
#include "gmm_em.hpp"
#undef CROPSIGHT_EM_NS

#include "cropsight/core/error.hpp"
#include "gmm_kernels.hpp"

namespace cropsight::segmentation {
namespace {

void check_input(const std::vector<Eigen::Vector3f>& points, const GmmConfig& cfg, const std::string& where) {
  if (cfg.components < 1) throw Error(where, "components must be >= 1");
  if (int(points.size()) < cfg.components)
    throw Error(where, "fewer points (" + std::to_string(points.size()) + ") than components (" +
                           std::to_string(cfg.components) + ")");
  for (const auto& p : points)
    if (!p.allFinite()) throw Error(where, "point with a non-finite coordinate");
}

}  // namespace

GmmModel gmm_initial_model(const std::vector<Eigen::Vector3f>& points, const GmmConfig& cfg, const std::string& where) {
  check_input(points, cfg, where);
  return em_portable::initial(points, cfg);
}

GmmResult fit_gmm(const std::vector<Eigen::Vector3f>& points, const GmmConfig& cfg, const std::string& where) {
  check_input(points, cfg, where);
  return em_avx2::available() ? em_avx2::fit(points, cfg) : em_portable::fit(points, cfg);
}

double gmm_mean_log_likelihood(const GmmModel& model, const std::vector<Eigen::Vector3f>& points) {
  const int k = model.size();
  std::vector<Eigen::Matrix3d> inv(k);
  std::vector<double> c(k);
  for (int j = 0; j < k; ++j) {
    inv[j] = model.covariances[j].inverse();
    c[j] = std::log(model.weights[j]) - 0.5 * std::log(model.covariances[j].determinant()) -
           1.5 * std::log(2.0 * std::numbers::pi);
  }
  double total = 0;
  std::vector<double> l(k);
  for (const auto& p : points) {
    const Eigen::Vector3d x = p.cast<double>();
    double mx = -std::numeric_limits<double>::infinity();
    for (int j = 0; j < k; ++j) {
      const Eigen::Vector3d d = x - model.means[j];
      l[j] = c[j] - 0.5 * d.dot(inv[j] * d);
      mx = std::max(mx, l[j]);
    }
    double s = 0;
    for (int j = 0; j < k; ++j) s += std::exp(l[j] - mx);
    total += mx + std::log(s);
  }
  return points.empty() ? 0.0 : total / double(points.size());
}

}  // namespace cropsight::segmentation
