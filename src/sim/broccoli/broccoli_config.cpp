#include "cropsight/sim/broccoli/broccoli_config.hpp"

#include <cmath>
#include <string>

#include "cropsight/core/error.hpp"
#include "cropsight/sim/broccoli/broccoli_randomize.hpp"

namespace cropsight::sim {

namespace {
void require(bool ok, const std::string& where, const std::string& what) {
  if (!ok) throw Error(where, what);
}
}  // namespace

void BroccoliSimConfig::validate(const std::string& where) const {
  require(camera.width > 0 && camera.height > 0 && camera.width <= 4096 && camera.height <= 4096, where,
          "camera.width/height must be in 1..4096");
  require(camera.hfov_deg > 1 && camera.hfov_deg < 170 && camera.vfov_deg > 1 && camera.vfov_deg < 170, where,
          "camera fields of view must be in (1, 170) degrees");
  require(camera.height_m > 0.2 && camera.height_m < 5, where, "camera.height_m must be in (0.2, 5) m");
  require(camera.supersample >= 1 && camera.supersample <= 4, where, "camera.supersample must be 1..4");
  require(camera.min_range_m >= 0 && camera.max_range_m > camera.min_range_m && camera.max_range_m < 65, where,
          "camera range must satisfy 0 <= min_range_m < max_range_m < 65");
  require(motion.fps > 0 && motion.fps <= 120, where, "motion.fps must be in (0, 120]");
  require(motion.speed_mps >= 0 && motion.speed_mps <= 5, where, "motion.speed_mps must be in [0, 5] m/s");
  require(motion.speed_jitter >= 0 && motion.height_jitter_m >= 0 && motion.lateral_jitter_m >= 0, where,
          "motion jitters must be >= 0");
  require(field.rows_under_camera >= 1 && field.rows_under_camera <= 8, where, "field.rows_under_camera must be 1..8");
  require(field.row_spacing_m >= 0.2 && field.in_row_spacing_m >= 0.1, where,
          "field.row_spacing_m must be >= 0.2 m and field.in_row_spacing_m >= 0.1 m");
  require(field.missing_plant_prob >= 0 && field.missing_plant_prob <= 1 && field.harvested_prob >= 0 &&
              field.harvested_prob <= 1,
          where, "field probabilities must be in [0, 1]");
  require(field.weed_density_m2 >= 0 && field.weed_density_m2 <= 200, where,
          "field.weed_density_m2 must be in [0, 200]");
  require(plant.leaf_count_min >= 0 && plant.leaf_count_max >= plant.leaf_count_min && plant.leaf_count_max <= 40,
          where, "plant.leaf_count_min/max must satisfy 0 <= min <= max <= 40");
  require(plant.inner_leaves_min >= 0 && plant.inner_leaves_max >= plant.inner_leaves_min, where,
          "plant.inner_leaves_min/max must satisfy 0 <= min <= max");
  require(plant.head_top_min_m > 0.05 && plant.head_top_max_m >= plant.head_top_min_m, where,
          "plant.head_top_min/max_m must satisfy 0.05 < min <= max");
  require(plant.leaf_length_min_m > 0 && plant.leaf_length_max_m >= plant.leaf_length_min_m, where,
          "plant.leaf_length_min/max_m must satisfy 0 < min <= max");
  require(plant.leaf_rim_step_min_m >= 0 && plant.leaf_rim_step_max_m >= plant.leaf_rim_step_min_m &&
              plant.leaf_rim_step_max_m <= 0.3,
          where, "plant.leaf_rim_step_min/max_m must satisfy 0 <= min <= max <= 0.3");
  require(plant.leaf_rim_clearance_m >= 0 && plant.leaf_rim_clearance_m <= 0.2, where,
          "plant.leaf_rim_clearance_m must be in [0, 0.2] m");
  require(plant.inner_leaf_gap_max_m >= 0 && plant.inner_leaf_gap_max_m <= 0.2, where,
          "plant.inner_leaf_gap_max_m must be in [0, 0.2] m");
  require(plant.leaf_rim_touch_prob >= 0 && plant.leaf_rim_touch_prob <= 1, where,
          "plant.leaf_rim_touch_prob must be in [0, 1]");
  require(head.diameter_min_mm >= 10 && head.diameter_max_mm > head.diameter_min_mm && head.diameter_max_mm <= 400,
          where, "head.diameter_min/max_mm must satisfy 10 <= min < max <= 400");
  require(head.mature_min_mm >= head.diameter_min_mm && head.mature_min_mm <= head.diameter_max_mm, where,
          "head.mature_min_mm must lie within [diameter_min_mm, diameter_max_mm]");
  require(head.ellipticity_max >= 0 && head.ellipticity_max < 0.5, where, "head.ellipticity_max must be in [0, 0.5)");
  require(head.dome_ratio_min > 0.05 && head.dome_ratio_max >= head.dome_ratio_min && head.dome_ratio_max <= 1.5, where,
          "head.dome_ratio_min/max must satisfy 0.05 < min <= max <= 1.5");
  require(head.floret_ratio > 0.03 && head.floret_ratio < 0.5, where, "head.floret_ratio must be in (0.03, 0.5)");
  require(soil.grid_m >= 0.002 && soil.grid_m <= 0.1, where, "soil.grid_m must be in [0.002, 0.1] m");
  require(soil.clod_size_min_m > 0 && soil.clod_size_max_m >= soil.clod_size_min_m, where,
          "soil.clod_size_min/max_m must satisfy 0 < min <= max");
  require(weed.size_min_m > 0 && weed.size_max_m >= weed.size_min_m, where,
          "weed.size_min/max_m must satisfy 0 < min <= max");
  require(sensor.noise_at_1m_m >= 0 && sensor.reference_reflectivity > 0 && sensor.background >= 0, where,
          "sensor noise parameters must be >= 0 (reference_reflectivity > 0)");
  require(sensor.amplitude_softness > 0, where, "sensor.amplitude_softness must be > 0");
  for (double p : {sensor.random_dropout, sensor.flying_prob, sensor.edge_dropout_prob, sensor.sunlight_dropout})
    require(p >= 0 && p <= 1, where, "sensor probabilities must be in [0, 1]");
  require(sensor.flying_prob + sensor.edge_dropout_prob <= 1, where,
          "sensor.flying_prob + sensor.edge_dropout_prob must be <= 1");
  require(sensor.model == "tof" || sensor.model == "stereo", where, "sensor.model must be tof or stereo");
  require(sensor.stereo_noise_at_1m_m >= 0 && sensor.stereo_hole_fraction >= 0 && sensor.stereo_hole_fraction < 1 &&
              sensor.stereo_hole_scale_px >= 1 && sensor.stereo_edge_dropout_prob >= 0 &&
              sensor.stereo_edge_dropout_prob <= 1,
          where, "sensor.stereo_* must be >= 0 (hole fraction < 1, hole scale >= 1 px, edge dropout <= 1)");
  require(camera.tilt_deg >= 0 && camera.tilt_deg <= 30, where, "camera.tilt_deg must be in [0, 30]");
  require(plant.leaf_blade_exponent > 0.1 && plant.leaf_blade_exponent <= 3 && plant.leaf_blade_fullness > 0.1 &&
              plant.leaf_blade_fullness <= 4,
          where, "plant.leaf_blade_exponent must be in (0.1, 3], plant.leaf_blade_fullness in (0.1, 4]");
  validate_randomize(randomize, where);
  require(light.ambient >= 0 && light.ambient <= 1, where, "light.ambient must be in [0, 1]");
}

}  // namespace cropsight::sim
