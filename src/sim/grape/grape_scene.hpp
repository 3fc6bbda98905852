#pragma once
// The grape simulator's scene (grape_scene.cpp) and its ray caster (grape_raycast.cpp): what
// simulate_grape_cloud composes. Everything in the camera frame (x right, y down, z forward),
// metres; pixel (u, v) looks along ((u + 0.5) / f, (v + 0.5) / f, 1), so the principal point is
// the pixel corner (0, 0) and u, v may be negative.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "cropsight/sim/grape/grape_sim.hpp"
#include "cropsight/sim/random.hpp"

namespace cropsight::sim::detail {

/// A berry or one link of the peduncle's chain.
struct GrapeSphere {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
  int label = kGrapeBerry;
  Eigen::Vector3f color{0, 0, 0};  ///< [0, 1], before shading
};

/// A flat, lobed leaf: the points c + x e1 + y e2 with (x/a)^2 + (y/b)^2 < (1 + 0.12 cos 5 phi)^2.
struct GrapeLeaf {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), e1 = Eigen::Vector3d::UnitX(), e2 = Eigen::Vector3d::UnitY();
  double a = 0.05, b = 0.04;  ///< m; semi-axes along e1, e2
  Eigen::Vector3f color{0, 0, 0};
};

struct GrapeScene {
  std::vector<GrapeSphere> spheres;  ///< the berries, then the peduncle's chain
  std::vector<GrapeLeaf> leaves;
  double backdrop_z = 1.0;  ///< m; the backdrop is the plane z = backdrop_z
  double backdrop_holes = 0.45;
  std::uint64_t backdrop_seed = 0;
  Eigen::Vector3d bunch_top = Eigen::Vector3d::Zero();        ///< where the peduncle meets the bunch
  Eigen::Vector3d peduncle_axis = -Eigen::Vector3d::UnitY();  ///< unit, from the bunch up
  double distance = 0;
  int berries = 0;
};

/// Builds the scene of one seed: bunch, peduncle, leaves and backdrop (cfg validated by the caller).
GrapeScene build_grape_scene(const GrapeSimConfig& cfg, std::uint64_t seed);

/// The pixel rectangle [u0, u0 + width) x [v0, v0 + height) that a bunch box and its peduncle
/// box span (Eq. 1 of the grape pipeline: the bunch's columns, from the peduncle's top to the
/// bunch's bottom), with a margin of 3 px.
struct PixelRect {
  int u0 = 0, v0 = 0, width = 0, height = 0;
};
PixelRect grape_roi(const GrapeScene& scene, double focal_px);

/// What one pixel sees.
struct GrapeHit {
  float depth = 0;  ///< m along z; 0 = no return (a hole in the backdrop)
  int label = kGrapeNoReturn;
  Eigen::Vector3f color{0, 0, 0};                      ///< [0, 1], shaded
  Eigen::Vector3f position = Eigen::Vector3f::Zero();  ///< m, noise-free
};

/// Casts one ray per pixel of `roi`, row-major (width x height hits).
std::vector<GrapeHit> cast_grape_scene(const GrapeScene& scene, double focal_px, const PixelRect& roi);

/// Colour of the world behind a hole in the backdrop (sky, far rows): smooth, varied.
Eigen::Vector3f far_color(std::uint64_t seed, double x, double y);

}  // namespace cropsight::sim::detail
