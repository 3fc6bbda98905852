#include "cropsight/sim/broccoli/broccoli_randomize.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "cropsight/core/error.hpp"
#include "cropsight/sim/random.hpp"

namespace cropsight::sim {

namespace {
// Its own stream: the field's, motion's and frames' draws (tags 1-30) are not shifted by it.
enum : std::int64_t { kRandomizeTag = 40 };

double draw(Rng& rng, const std::vector<double>& r) { return rng.uniform(r[0], r[1]); }

// A window [lo, hi] inside range r whose width is a drawn fraction of r's: the sequence's plants
// then vary among themselves as a preset's do, around a drawn centre.
std::pair<double, double> window(Rng& rng, const std::vector<double>& r, double min_frac, double max_frac) {
  const double span = r[1] - r[0];
  const double w = span * rng.uniform(min_frac, max_frac);
  const double lo = r[0] + (span - w) * rng.uniform();
  return {lo, lo + w};
}
}  // namespace

const char* leaf_family_name(LeafFamily f) {
  switch (f) {
    case LeafFamily::pointed:
      return "pointed";
    case LeafFamily::broad:
      return "broad";
    case LeafFamily::obovate:
      return "obovate";
  }
  return "?";
}

void validate_randomize(const SimRandomizeConfig& r, const std::string& where) {
  auto range = [&](const std::vector<double>& v, const char* name, double lo, double hi) {
    if (v.size() != 2 || !(v[0] <= v[1]) || v[0] < lo || v[1] > hi)
      throw Error(where, std::string("randomize.") + name + " must be {min, max} with " + std::to_string(lo) +
                             " <= min <= max <= " + std::to_string(hi));
  };
  range(r.camera_height_m, "camera_height_m", 0.6, 4.0);
  range(r.camera_tilt_deg, "camera_tilt_deg", 0, 30);
  range(r.row_spacing_m, "row_spacing_m", 0.2, 3);
  range(r.in_row_spacing_m, "in_row_spacing_m", 0.1, 2);
  range(r.leaf_count, "leaf_count", 0, 40);
  range(r.leaf_length_m, "leaf_length_m", 0.02, 1.5);
  range(r.leaf_elevation_deg, "leaf_elevation_deg", 0, 90);
  range(r.leaf_droop_deg, "leaf_droop_deg", 0, 150);
  range(r.leaf_ruffle_m, "leaf_ruffle_m", 0, 0.1);
  range(r.plant_height_m, "plant_height_m", 0.2, 1.5);
  range(r.head_diameter_mm, "head_diameter_mm", 10, 400);
  range(r.head_dome_ratio, "head_dome_ratio", 0.06, 1.5);
  range(r.floret_ratio, "floret_ratio", 0.031, 0.49);
  range(r.floret_height, "floret_height", 0, 2);
  range(r.head_below_canopy_m, "head_below_canopy_m", 0, 0.5);
  range(r.inner_leaves, "inner_leaves", 0, 20);
  range(r.soil_roughness_m, "soil_roughness_m", 0, 0.2);
  range(r.clod_density_m2, "clod_density_m2", 0, 1000);
  range(r.weed_density_m2, "weed_density_m2", 0, 200);
  range(r.tof_noise_at_1m_m, "tof_noise_at_1m_m", 0, 0.1);
  range(r.tof_flying_prob, "tof_flying_prob", 0, 1);
  range(r.tof_amplitude_min, "tof_amplitude_min", 0, 1);
  range(r.random_dropout, "random_dropout", 0, 0.5);
  range(r.stereo_noise_at_1m_m, "stereo_noise_at_1m_m", 0, 0.1);
  range(r.stereo_hole_fraction, "stereo_hole_fraction", 0, 0.6);
  if (r.leaf_family_weights.size() != 3 ||
      std::any_of(r.leaf_family_weights.begin(), r.leaf_family_weights.end(), [](double w) { return !(w >= 0); }) ||
      r.leaf_family_weights[0] + r.leaf_family_weights[1] + r.leaf_family_weights[2] <= 0)
    throw Error(where, "randomize.leaf_family_weights must be three weights >= 0 with a positive sum");
  for (double p : {r.one_row_prob, r.stereo_prob, r.sunlight_prob})
    if (!(p >= 0 && p <= 1)) throw Error(where, "randomize probabilities must be in [0, 1]");
  if (r.plant_height_m[0] - r.head_below_canopy_m[1] <= 0.17)
    throw Error(where,
                "randomize: plant_height_m min - head_below_canopy_m max must exceed 0.17 m (the lowest head apex then "
                "stays above 5 cm)");
}

// Draws in a fixed order, every value unconditionally (as the field does), so that changing one
// range never shifts the others' draws.
BroccoliSimConfig draw_randomized_config(const BroccoliSimConfig& base, std::uint64_t seed, LeafFamily* family) {
  if (!base.randomize.enabled) return base;
  const SimRandomizeConfig& R = base.randomize;
  BroccoliSimConfig c = base;
  Rng rng(derive_seed(seed, {kRandomizeTag}));

  // Camera.
  c.camera.height_m = draw(rng, R.camera_height_m);
  c.camera.tilt_deg = draw(rng, R.camera_tilt_deg);
  c.camera.tilt_azimuth_deg = rng.uniform(0.0, 360.0);

  // Field layout.
  c.field.rows_under_camera = rng.bernoulli(R.one_row_prob) ? 1 : 2;
  c.field.row_spacing_m = draw(rng, R.row_spacing_m);
  c.field.in_row_spacing_m = draw(rng, R.in_row_spacing_m);
  c.field.weed_density_m2 = draw(rng, R.weed_density_m2);

  // Leaves: one shape family per sequence, then its continuous parameters.
  const auto& fw = R.leaf_family_weights;
  const double pick = rng.uniform() * (fw[0] + fw[1] + fw[2]);
  const LeafFamily fam = pick < fw[0]           ? LeafFamily::pointed
                         : pick < fw[0] + fw[1] ? LeafFamily::broad
                                                : LeafFamily::obovate;
  const double u_w = rng.uniform(), u_e = rng.uniform(), u_f = rng.uniform();
  switch (fam) {
    case LeafFamily::pointed:  // narrow, widest mid-blade, tapering to a point
      c.plant.leaf_width_ratio = 0.20 + 0.12 * u_w;
      c.plant.leaf_blade_exponent = 0.85 + 0.2 * u_e;
      c.plant.leaf_blade_fullness = 1.1 + 0.5 * u_f;
      break;
    case LeafFamily::broad:  // wide, widest near the base, rounded outline
      c.plant.leaf_width_ratio = 0.50 + 0.20 * u_w;
      c.plant.leaf_blade_exponent = 0.45 + 0.2 * u_e;
      c.plant.leaf_blade_fullness = 0.4 + 0.35 * u_f;
      break;
    case LeafFamily::obovate:  // the presets' outline, width varied
      c.plant.leaf_width_ratio = 0.34 + 0.16 * u_w;
      c.plant.leaf_blade_exponent = 0.7;
      c.plant.leaf_blade_fullness = 1.0;
      break;
  }
  if (family) *family = fam;
  const auto [count_lo, count_hi] = window(rng, R.leaf_count, 0.2, 0.5);
  c.plant.leaf_count_min = int(std::lround(count_lo));
  c.plant.leaf_count_max = std::max(c.plant.leaf_count_min, int(std::lround(count_hi)));
  std::tie(c.plant.leaf_length_min_m, c.plant.leaf_length_max_m) = window(rng, R.leaf_length_m, 0.2, 0.6);
  std::tie(c.plant.leaf_elevation_min_deg, c.plant.leaf_elevation_max_deg) =
      window(rng, R.leaf_elevation_deg, 0.3, 0.7);
  std::tie(c.plant.leaf_droop_min_deg, c.plant.leaf_droop_max_deg) = window(rng, R.leaf_droop_deg, 0.3, 0.7);
  c.plant.leaf_ruffle_m = draw(rng, R.leaf_ruffle_m);
  c.plant.plant_height_m = draw(rng, R.plant_height_m);
  const auto [inner_lo, inner_hi] = window(rng, R.inner_leaves, 0.2, 0.6);
  c.plant.inner_leaves_min = int(std::lround(inner_lo));
  c.plant.inner_leaves_max = std::max(c.plant.inner_leaves_min, int(std::lround(inner_hi)));

  // Heads: a size window of the range (immature below its lower third, mature above), the dome,
  // the floret bumps and how deep the heads sit in the canopy.
  const auto [d_lo, d_hi] = window(rng, R.head_diameter_mm, 0.5, 1.0);
  c.head.diameter_min_mm = d_lo;
  c.head.diameter_max_mm = std::max(d_hi, d_lo + 1.0);
  c.head.mature_min_mm = d_lo + (c.head.diameter_max_mm - d_lo) * rng.uniform(0.2, 0.45);
  c.head.mature_mean_mm = 0.5 * (c.head.mature_min_mm + c.head.diameter_max_mm);
  c.head.mature_std_mm = 0.25 * (c.head.diameter_max_mm - c.head.mature_min_mm);
  c.head.immature_prob = rng.uniform(0.1, 0.4);
  std::tie(c.head.dome_ratio_min, c.head.dome_ratio_max) = window(rng, R.head_dome_ratio, 0.2, 0.5);
  c.head.floret_ratio = draw(rng, R.floret_ratio);
  c.head.floret_height = draw(rng, R.floret_height);
  const double below = draw(rng, R.head_below_canopy_m);
  c.plant.head_top_max_m = c.plant.plant_height_m - below;
  c.plant.head_top_min_m = c.plant.head_top_max_m - rng.uniform(0.05, 0.12);

  // Soil.
  c.soil.roughness_m = draw(rng, R.soil_roughness_m);
  c.soil.clod_density_m2 = draw(rng, R.clod_density_m2);

  // Sensor.
  const bool stereo = rng.bernoulli(R.stereo_prob);
  c.sensor.model = stereo ? "stereo" : "tof";
  c.sensor.noise_at_1m_m = draw(rng, R.tof_noise_at_1m_m);
  c.sensor.flying_prob = draw(rng, R.tof_flying_prob);
  c.sensor.edge_dropout_prob = (1.0 - c.sensor.flying_prob) * rng.uniform(0.2, 0.8);
  c.sensor.amplitude_min = draw(rng, R.tof_amplitude_min);
  c.sensor.random_dropout = draw(rng, R.random_dropout);
  c.sensor.stereo_noise_at_1m_m = draw(rng, R.stereo_noise_at_1m_m);
  c.sensor.stereo_hole_fraction = draw(rng, R.stereo_hole_fraction);
  c.sensor.stereo_hole_scale_px = rng.uniform(6.0, 20.0);
  c.sensor.sunlight = rng.bernoulli(R.sunlight_prob);
  c.light.sun_elevation_deg = rng.uniform(25.0, 80.0);
  c.light.sun_azimuth_deg = rng.uniform(0.0, 360.0);
  return c;
}

}  // namespace cropsight::sim
