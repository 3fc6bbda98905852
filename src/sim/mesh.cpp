#include "cropsight/sim/mesh.hpp"

#include <cmath>

namespace cropsight::sim {

void Mesh::append(const Mesh& other) {
  const auto offset = std::uint32_t(position.size());
  position.insert(position.end(), other.position.begin(), other.position.end());
  normal.insert(normal.end(), other.normal.begin(), other.normal.end());
  color.insert(color.end(), other.color.begin(), other.color.end());
  reflectivity.insert(reflectivity.end(), other.reflectivity.begin(), other.reflectivity.end());
  for (const auto& t : other.tri) tri.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  tri_label.insert(tri_label.end(), other.tri_label.begin(), other.tri_label.end());
  tri_kind.insert(tri_kind.end(), other.tri_kind.begin(), other.tri_kind.end());
  box_min = box_min.cwiseMin(other.box_min);
  box_max = box_max.cwiseMax(other.box_max);
}

void Mesh::compute_normals() {
  for (auto& n : normal) n.setZero();
  for (const auto& t : tri) {
    const Eigen::Vector3f e1 = position[t[1]] - position[t[0]];
    const Eigen::Vector3f e2 = position[t[2]] - position[t[0]];
    const Eigen::Vector3f n = e1.cross(e2);  // length = 2 * area: area weighting for free
    for (auto i : t) normal[i] += n;
  }
  for (auto& n : normal) {
    const float len = n.norm();
    n = len > 0 ? Eigen::Vector3f(n / len) : Eigen::Vector3f(0, 0, 1);
  }
}

void Mesh::shade(const Eigen::Vector3f& light_dir, float ambient) {
  const Eigen::Vector3f l = light_dir.normalized();
  for (std::size_t i = 0; i < color.size(); ++i) {
    const float lambert = std::abs(normal[i].dot(l));
    color[i] *= ambient + (1.0f - ambient) * lambert;
  }
}

}  // namespace cropsight::sim
