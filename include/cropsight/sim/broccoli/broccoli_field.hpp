#pragma once
// The broccoli field: where plants stand, what each plant looks like, and the soil around them.
//
// Everything is a pure function of (seed, config, integer coordinates): plant (row r, slot j)
// draws from derive_seed(seed, {plant, r, j}), soil tile t from derive_seed(seed, {tile, t}).
// So a plant looks the same whichever frame first needs it, and a longer sequence with the same
// seed starts with the same field. Field frame: x along the row, y across, z up, z = 0 = mean soil.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <vector>

#include "cropsight/sim/broccoli/broccoli_config.hpp"
#include "cropsight/sim/mesh.hpp"

namespace cropsight::sim {

/// A broccoli head. The modelled head is a dome of florets on an elliptic outline (semi-axes
/// a >= b), tilted by `orientation`, resting on the stem at `base`.
struct HeadSpec {
  int id = 0;                                                 ///< instance id (label value), > 0
  Eigen::Vector3d base = Eigen::Vector3d::Zero();             ///< field frame: centre of the dome's rim plane
  Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();  ///< head frame -> field frame (head z = axis)
  double semi_a = 0.07, semi_b = 0.07;  ///< m; outline semi-axes (head frame x, y) before the final scale
  double dome_height = 0.04;            ///< m; height of the smooth dome above the rim plane
  double floret_radius = 0.01;          ///< m
  double floret_height = 0.5;           ///< bump height / floret radius
  double target_diameter_mm = 140;      ///< drawn diameter; the mesh is scaled to measure exactly this
  bool mature = true;
  bool purple = false;
  double tilt_deg = 0.0;
  Eigen::Vector3f color{55, 85, 60};
  std::uint64_t seed = 0;
  Eigen::Vector3d apex = Eigen::Vector3d::Zero();  ///< field frame: top of the smooth dome on the head axis
  // Filled when the head mesh is built (build_plant):
  double caliper_major_mm = 0;  ///< widest caliper width across the head axis
  double caliper_minor_mm = 0;  ///< caliper width perpendicular to the widest
  double diameter_mm = 0;       ///< (major + minor) / 2, as growers measure
};

struct PlantSpec {
  int row = 0;                                   ///< row index (row r at y = y0 + r * row_spacing)
  int slot = 0;                                  ///< planting slot along the row
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  ///< stem position, field frame
  bool harvested = false;                        ///< head already cut: a stump, no head
  bool has_head = false;
  HeadSpec head;
  double stump_height = 0.0;  ///< m; for harvested plants
  std::uint64_t seed = 0;
};

class BroccoliField {
 public:
  BroccoliField(BroccoliSimConfig config, std::uint64_t seed);

  const BroccoliSimConfig& config() const { return cfg_; }
  std::uint64_t seed() const { return seed_; }

  /// y of row r.
  double row_y(int row) const;
  /// Row indices whose plants can appear within |y| <= half_width.
  std::vector<int> rows_within(double half_width) const;
  /// Plant specs (no meshes) of the given rows with stem x in [x0, x1], sorted by (slot, row).
  /// Missing plants are omitted; head ids are left 0 (the simulator numbers them).
  std::vector<PlantSpec> plants(const std::vector<int>& rows, double x0, double x1) const;

  /// Builds the plant's mesh (leaves, stem, head or stump). For a plant with a head, the mesh's
  /// head triangles carry `spec.head.id` and `spec.head`'s measured fields are filled.
  std::shared_ptr<const Mesh> build_plant(PlantSpec& spec) const;

  /// Soil (with clods) and weeds of tile t: x in [t, t+1] * tile_length(), |y| <= half_width.
  std::shared_ptr<const Mesh> build_tile(int tile, double half_width) const;
  double tile_length() const { return 0.5; }

  /// Smooth soil height without clods (m), for placing objects.
  double soil_base_height(double x, double y) const;

 private:
  BroccoliSimConfig cfg_;
  std::uint64_t seed_;
};

/// Caliper widths of the points' projections on the plane orthogonal to `axis`: the widest
/// direction (searched in 0.5 deg steps) and the one perpendicular to it, in metres.
std::pair<double, double> caliper_widths(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& center,
                                         const Eigen::Matrix3f& head_to_field);

}  // namespace cropsight::sim
