#pragma once
// Internal: k-means++ seeding (D^2 sampling) shared by k-means and fuzzy c-means.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace cropsight::segmentation {
std::vector<Eigen::Vector3d> kmeanspp_seeds(const std::vector<Eigen::Vector3f>& points, int k, std::uint32_t seed);
}
