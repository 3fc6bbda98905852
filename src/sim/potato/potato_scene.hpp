#pragma once
// Internal: the potato scene's meshes and truth (see potato_sim.hpp for the frames).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "cropsight/sim/mesh.hpp"
#include "cropsight/sim/potato/potato_sim.hpp"

namespace cropsight::sim::detail {

struct PotatoSpec {
  int id = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();    ///< world frame
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< columns: length, width, thickness directions
  double length = 0, width = 0, thickness = 0;         ///< full axes, m
  int sprouts = 0;
};

struct PotatoSceneModel {
  std::vector<PotatoSpec> potatoes;  ///< [0] is the target
  Mesh mesh;                         ///< everything, one mesh (labels = potato ids)
};

/// Builds the scene of `cfg` from `seed`: potatoes, their strings, roots, backdrop.
PotatoSceneModel build_potato_scene(const PotatoSimConfig& cfg, std::uint64_t seed);

}  // namespace cropsight::sim::detail
