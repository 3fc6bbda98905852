#include "cropsight/features/geometric.hpp"

#include <algorithm>
#include <cmath>

#include "cropsight/geometry/pca.hpp"

namespace cropsight::features {

void compute_geometric_features(const OrganizedCloud& cloud, std::span<const int> indices, GeometricWorkspace& ws,
                                float* out) {
  std::fill(out, out + kGeometricFeatures, 0.0f);
  if (indices.size() < 3) return;
  const int w = cloud.width, h = cloud.height;
  const std::size_t npix = cloud.size();
  if (ws.mask.size() != npix) ws.mask.assign(npix, 0);
  for (int i : indices) ws.mask[i] = 1;
  const unsigned char* M = ws.mask.data();
  const bool normals = cloud.has_normals();
  auto P = [&](int i) { return Eigen::Vector3d(cloud.x[i], cloud.y[i], cloud.z[i]); };
  auto has_n = [&](int i) { return normals && std::isfinite(cloud.nx[i]); };
  auto N = [&](int i) { return Eigen::Vector3d(cloud.nx[i], cloud.ny[i], cloud.nz[i]); };

  double area = 0.0;
  long sides = 0;
  double angle_sum = 0.0;
  long angle_pairs = 0;
  double convex = 0.0;
  for (int i : indices) {
    const int u = i % w, v = i / w;
    const bool right = u + 1 < w && M[i + 1];
    const bool down = v + 1 < h && M[i + w];
    // Boundary sides of the mask (outside the grid counts as outside the mask).
    sides += (u == 0 || !M[i - 1]) + !right + (v == 0 || !M[i - w]) + !down;
    const Eigen::Vector3d p = P(i);
    if (right && down && M[i + w + 1]) {
      const Eigen::Vector3d p10 = P(i + 1), p01 = P(i + w), p11 = P(i + w + 1);
      area += 0.5 * ((p10 - p).cross(p11 - p)).norm() + 0.5 * ((p11 - p).cross(p01 - p)).norm();
    }
    if (!has_n(i)) continue;
    const Eigen::Vector3d ni = N(i);
    for (int j : {right ? i + 1 : -1, down ? i + w : -1}) {
      if (j < 0 || !has_n(j)) continue;
      const Eigen::Vector3d nj = N(j);
      angle_sum += std::acos(std::clamp(ni.dot(nj), -1.0, 1.0));
      const double c = (P(j) - p).dot(nj - ni);
      convex += std::abs(c) <= 1e-12 ? 0.5 : (c > 0 ? 1.0 : 0.0);
      ++angle_pairs;
    }
  }
  const double count = double(indices.size());
  const double perimeter = double(sides) * M_PI / 4.0;
  out[0] = float(area);
  out[1] = perimeter > 0 ? float(4.0 * M_PI * count / (perimeter * perimeter)) : 0.0f;
  out[2] = angle_pairs ? float(angle_sum / double(angle_pairs)) : 0.0f;
  out[3] = angle_pairs ? float(convex / double(angle_pairs)) : 0.0f;

  // Symmetry: skewness along the two major principal axes.
  const auto pc = geometry::pca(indices.size(), [&](std::size_t q) { return P(indices[q]); });
  double skew_sum = 0.0;
  for (int axis = 1; axis <= 2; ++axis) {
    const Eigen::Vector3d e = pc.axes.col(axis);
    const double var = pc.eigenvalues(axis);
    if (!(var > 0.0)) continue;
    double m3 = 0.0;
    for (int i : indices) {
      const double t = (P(i) - pc.mean).dot(e);
      m3 += t * t * t;
    }
    m3 /= count;
    skew_sum += std::abs(m3 / std::pow(var, 1.5));
  }
  out[4] = float(std::exp(-skew_sum / 2.0));

  for (int i : indices) ws.mask[i] = 0;
}

}  // namespace cropsight::features
