#pragma once
// A curved, cupped, ruffled leaf as a triangle strip grid (used for broccoli leaves and weeds).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cropsight/sim/mesh.hpp"
#include "cropsight/sim/random.hpp"

namespace cropsight::sim::detail {

struct LeafShape {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  ///< field frame, where the petiole leaves the stem
  double azimuth = 0;                               ///< rad; horizontal direction of the leaf at its base
  double yaw_bend = 0;                              ///< rad; change of azimuth from base to tip (sideways curve)
  double length = 0.3;                              ///< m; along the midrib, petiole included
  double width = 0.12;                              ///< m; widest blade width
  double petiole = 0.2;                             ///< fraction of the length that is bare petiole
  double elevation0 = 0.9;                          ///< rad; midrib angle above horizontal at the base
  double elevation1 = 0.1;      ///< rad; at the tip (> pi/2 means the leaf curls back over its base)
  double bend_power = 1.5;      ///< how the angle moves from elevation0 to elevation1 along the leaf
  double blade_exponent = 0.7;  ///< width(u) = sin(pi u^e): e < 1 widest towards the tip, ~1 mid-blade
  double blade_fullness = 1.0;  ///< the width profile raised to this: < 1 rounded, > 1 pointed
  double cup = 0.25;            ///< margin lift as a fraction of the half width
  double ruffle = 0.006;        ///< m; amplitude of the wavy margin
  double twist = 0.0;           ///< rad; roll of the blade about the midrib at the tip
  int segments = 22;            ///< along the midrib
  int across = 9;               ///< across the blade (odd: a vertex row on the midrib)
  Eigen::Vector3f color{95, 125, 120};
  Eigen::Vector3f midrib_color{170, 190, 165};
  float reflectivity = 0.55f;
};

/// Appends the leaf to `mesh` (label 0, `kind`); per-vertex colour speckle from `rng`.
void add_leaf(Mesh& mesh, const LeafShape& leaf, SurfaceKind kind, Rng& rng);

/// Unit direction of the midrib at arc-length fraction s in [0, 1] (what add_leaf follows).
Eigen::Vector3d midrib_tangent(const LeafShape& leaf, double s);

/// Field z of the leaf's midrib where its horizontal distance from the vertical line through
/// `axis` (x, y) first reaches `radius`, interpolated between the vertices add_leaf places; NaN
/// when the midrib never gets that far (or starts beyond it).
double midrib_z_at_radius(const LeafShape& leaf, const Eigen::Vector2d& axis, double radius);

}  // namespace cropsight::sim::detail
