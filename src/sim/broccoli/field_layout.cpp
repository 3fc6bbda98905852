// Where plants stand and what each is drawn to be (BroccoliField::plants), and the smooth soil.
#include <algorithm>
#include <cmath>

#include "cropsight/sim/broccoli/broccoli_field.hpp"
#include "cropsight/sim/random.hpp"
#include "sim/angles.hpp"
#include "sim/value_noise.hpp"

namespace cropsight::sim {

namespace {
// Stream tags for derive_seed: one per kind of object, so that streams never overlap.
enum : std::int64_t { kRowTag = 1, kPlantTag = 2, kPlantMeshTag = 3 };
}  // namespace

BroccoliField::BroccoliField(BroccoliSimConfig config, std::uint64_t seed) : cfg_(std::move(config)), seed_(seed) {
  cfg_.validate("sim config");
}

double BroccoliField::row_y(int row) const {
  const double first = -0.5 * (cfg_.field.rows_under_camera - 1) * cfg_.field.row_spacing_m;
  return first + row * cfg_.field.row_spacing_m;
}

std::vector<int> BroccoliField::rows_within(double half_width) const {
  // A plant reaches at most about one leaf length plus its wobble beyond its row.
  const double reach = cfg_.plant.leaf_length_max_m + 3 * cfg_.field.row_wobble_m + 0.05;
  std::vector<int> rows;
  const int span = int(std::ceil((half_width + reach) / cfg_.field.row_spacing_m)) + cfg_.field.rows_under_camera + 1;
  for (int r = -span; r <= span; ++r)
    if (std::abs(row_y(r)) <= half_width + reach) rows.push_back(r);
  return rows;
}

std::vector<PlantSpec> BroccoliField::plants(const std::vector<int>& rows, double x0, double x1) const {
  const auto& F = cfg_.field;
  const auto& P = cfg_.plant;
  const auto& H = cfg_.head;
  std::vector<PlantSpec> out;
  for (int r : rows) {
    Rng row_rng(derive_seed(seed_, {kRowTag, r}));
    const double phase = row_rng.uniform(0.0, F.in_row_spacing_m);
    const double margin = 4 * F.spacing_jitter_m + 0.01;
    const int j0 = int(std::floor((x0 - phase - margin) / F.in_row_spacing_m));
    const int j1 = int(std::ceil((x1 - phase + margin) / F.in_row_spacing_m));
    for (int j = j0; j <= j1; ++j) {
      Rng rng(derive_seed(seed_, {kPlantTag, r, j}));
      // Draw every value unconditionally, in a fixed order, so that one option (e.g. the
      // missing-plant probability) never shifts the others.
      const bool missing = rng.bernoulli(F.missing_plant_prob);
      PlantSpec s;
      s.row = r;
      s.slot = j;
      s.xy = {phase + j * F.in_row_spacing_m + rng.normal(0.0, F.spacing_jitter_m),
              row_y(r) + rng.normal(0.0, F.row_wobble_m)};
      s.harvested = rng.bernoulli(F.harvested_prob);
      s.stump_height = rng.uniform(0.18, 0.32);
      s.seed = derive_seed(seed_, {kPlantMeshTag, r, j});
      HeadSpec& h = s.head;
      h.mature = !rng.bernoulli(H.immature_prob);
      const double u_imm = rng.uniform();
      double d = H.mature_mean_mm + H.mature_std_mm * rng.normal();
      const double lo = H.mature_min_mm, hi = H.diameter_max_mm;
      if (d < lo || d > hi) d = lo + (hi - lo) * rng.uniform();  // rare tails: uniform in the window
      h.target_diameter_mm = h.mature ? d : H.diameter_min_mm + (H.mature_min_mm - H.diameter_min_mm) * u_imm;
      const double e = rng.uniform(0.0, H.ellipticity_max);
      const double R = 0.5e-3 * h.target_diameter_mm;
      h.semi_a = R * (1 + e);
      h.semi_b = R * (1 - e);
      h.dome_height = R * rng.uniform(H.dome_ratio_min, H.dome_ratio_max);
      h.floret_radius = R * H.floret_ratio * rng.uniform(0.9, 1.1);
      h.floret_height = H.floret_height;
      h.tilt_deg = rng.uniform(0.0, H.tilt_max_deg);
      const double tilt_dir = rng.uniform(0.0, 2 * 3.141592653589793);
      const double spin = rng.uniform(0.0, 2 * 3.141592653589793);
      h.orientation =
          (Eigen::AngleAxisd(h.tilt_deg * kDeg, Eigen::Vector3d(std::cos(tilt_dir), std::sin(tilt_dir), 0)) *
           Eigen::AngleAxisd(spin, Eigen::Vector3d::UnitZ()))
              .toRotationMatrix();
      const double top = rng.uniform(P.head_top_min_m, P.head_top_max_m) - (h.mature ? 0.0 : 0.04);
      // The apex is fixed here; the base follows when the mesh is built (the dome height is
      // final only after sizing).
      h.apex = {s.xy.x(), s.xy.y(), top};
      h.base = h.apex;
      h.purple = rng.bernoulli(H.purple_prob);
      const double g = rng.uniform(0.8, 1.15);
      h.color = h.purple ? Eigen::Vector3f(float(78 * g), float(66 * g), float(88 * g))
                         : Eigen::Vector3f(float(rng.uniform(45, 62) * g), float(rng.uniform(78, 96) * g),
                                           float(rng.uniform(52, 72) * g));
      h.seed = s.seed;
      s.has_head = !s.harvested;
      if (missing || s.xy.x() < x0 || s.xy.x() > x1) continue;
      out.push_back(s);
    }
  }
  std::sort(out.begin(), out.end(), [](const PlantSpec& a, const PlantSpec& b) {
    if (a.xy.x() != b.xy.x()) return a.xy.x() < b.xy.x();
    return a.row < b.row;
  });
  return out;
}

double BroccoliField::soil_base_height(double x, double y) const {
  const auto& S = cfg_.soil;
  const std::uint64_t s = derive_seed(seed_, {10});
  const double rough = S.roughness_m * detail::fbm(s, x / S.roughness_scale_m, y / S.roughness_scale_m, 4);
  const double ridge =
      S.ridge_height_m * 0.5 * std::cos(2 * 3.141592653589793 * (y - row_y(0)) / cfg_.field.row_spacing_m);
  return rough + ridge;
}

}  // namespace cropsight::sim
