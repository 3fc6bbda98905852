// Least-squares paraboloid apex (see dome_apex.hpp).
#include "cropsight/measure/dome_apex.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace cropsight::measure {

std::optional<Eigen::Vector3f> fit_dome_apex(std::span<const Eigen::Vector3f> points) {
  if (points.size() < std::size_t(DomeApexLimits::kMinPoints)) return std::nullopt;
  double mx = 0.0, my = 0.0;
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  for (const auto& p : points) {
    mx += p.x(), my += p.y();
    x_lo = std::min(x_lo, double(p.x())), x_hi = std::max(x_hi, double(p.x()));
    y_lo = std::min(y_lo, double(p.y())), y_hi = std::max(y_hi, double(p.y()));
  }
  mx /= double(points.size()), my /= double(points.size());
  // Normal equations of z = [r², x, y, 1]·[k, b, c, d], in double (centred coordinates are
  // centimetres; r² is a few cm², so the 4×4 system is well conditioned).
  Eigen::Matrix4d ata = Eigen::Matrix4d::Zero();
  Eigen::Vector4d atz = Eigen::Vector4d::Zero();
  for (const auto& p : points) {
    const double x = double(p.x()) - mx, y = double(p.y()) - my;
    const Eigen::Vector4d a(x * x + y * y, x, y, 1.0);
    ata.noalias() += a * a.transpose();
    atz.noalias() += a * double(p.z());
  }
  const Eigen::LDLT<Eigen::Matrix4d> ldlt(ata);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return std::nullopt;
  const Eigen::Vector4d s = ldlt.solve(atz);
  if (!s.allFinite()) return std::nullopt;
  const double k = s[0];
  if (!(k >= 1.0 / (2.0 * DomeApexLimits::kMaxRadius) && k <= 1.0 / (2.0 * DomeApexLimits::kMinRadius)))
    return std::nullopt;
  const double ax = -s[1] / (2.0 * k), ay = -s[2] / (2.0 * k);
  const double gx = 0.5 * (x_hi - x_lo), gy = 0.5 * (y_hi - y_lo);
  if (ax + mx < x_lo - gx || ax + mx > x_hi + gx || ay + my < y_lo - gy || ay + my > y_hi + gy) return std::nullopt;
  const double az = s[3] - k * (ax * ax + ay * ay);  // the paraboloid's value at its apex
  return Eigen::Vector3f(float(ax + mx), float(ay + my), float(az));
}

}  // namespace cropsight::measure
