#include "cropsight/pipeline/seedling/seedling_config.hpp"

#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"

namespace cropsight::pipeline {

void validate_seedling_config(const SeedlingConfig& c, const std::string& where) {
  auto fail = [&](const std::string& key, const std::string& problem) {
    throw Error(where, "'" + key + "' " + problem);
  };
  auto num = [](double v) { return cropsight::detail::format_value(v); };
  // Real numbers: finite and inside [lo, hi] (NaN fails every comparison).
  auto real = [&](const char* key, double v, double lo, double hi) {
    if (!(v >= lo && v <= hi)) fail(key, "must be in [" + num(lo) + ", " + num(hi) + "], got " + num(v));
  };
  auto integer = [&](const char* key, long v, long lo, long hi) {
    if (v < lo || v > hi)
      fail(key, "must be in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " + std::to_string(v));
  };
  stereo::validate_disparity_config(c.disparity, where, "disparity.");
  real("min_depth", c.min_depth, 1e-3, 1e3);
  real("max_depth", c.max_depth, 1e-3, 1e3);
  if (!(c.max_depth > c.min_depth))
    fail("max_depth", "(" + num(c.max_depth) + ") must be greater than min_depth (" + num(c.min_depth) + ")");
  integer("ransac_iterations", c.ransac_iterations, 1, 1000000);
  real("ransac_threshold", c.ransac_threshold, 1e-6, 10);
  integer("ransac_sample", c.ransac_sample, 3, 10000000);
  real("min_height", c.min_height, 0, 10);
  real("max_height", c.max_height, 0, 10);
  if (!(c.max_height > c.min_height))
    fail("max_height", "(" + num(c.max_height) + ") must be greater than min_height (" + num(c.min_height) + ")");
  integer("candidate_open", c.candidate_open, 0, 50);
  real("candidate_min_exg", c.candidate_min_exg, -1, 2);  // (2G-R-B)/(R+G+B) lies in [-1, 2]
  integer("sampling.target_points", c.sampling.target_points, 1, kMaxSampledPoints);
  integer("sampling.max_points_per_box", c.sampling.max_points_per_box, 0, 1 << 30);
  real("sampling.min_box_size", c.sampling.min_box_size, 1e-9, 1e3);
  // K can never exceed the points the GMM is fitted on (the down-sampled candidates).
  integer("gmm.components", c.gmm.components, 1, std::min(kMaxGmmComponents, c.sampling.target_points));
  integer("gmm.max_iterations", c.gmm.max_iterations, 1, 100000);
  real("gmm.tolerance", c.gmm.tolerance, 0, 1);
  real("gmm.min_variance", c.gmm.min_variance, 0, 1);
  integer("min_component_points", c.min_component_points, 1, kMaxSampledPoints);
  real("height_ratio", c.height_ratio, 0, 1);
  real("join_distance", c.join_distance, 1e-6, 10);
  integer("outlier.mean_k", c.outlier.mean_k, 1, 10000);
  real("outlier.std_mul", c.outlier.std_mul, 0, 1e3);
  // The top-view raster spans the seedling's extent in cells: a tiny cell makes it huge.
  real("topview_cell", c.topview_cell, 1e-4, 1);
  integer("topview_dilate", c.topview_dilate, 0, 100);
}

SeedlingConfig load_seedling_config(const std::string& preset) {
  const auto path = io::find_preset(preset);
  SeedlingConfig cfg;
  apply_config(cfg, io::load_config_map(path), path.string());
  validate_seedling_config(cfg, path.string());
  return cfg;
}

}  // namespace cropsight::pipeline
