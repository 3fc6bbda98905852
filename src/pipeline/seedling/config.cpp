#include "cropsight/pipeline/seedling/config.hpp"

#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"

namespace cropsight::pipeline::seedling {

void Config::validate(const std::string& where) const {
  const Config& c = *this;
  stereo::validate_disparity_config(c.disparity, where, "disparity.");
  check_config(c, where);
  cropsight::detail::check_range(where, "max_depth", c.max_depth, Range::above(c.min_depth, "min_depth"));
  cropsight::detail::check_range(where, "max_height", c.max_height, Range::above(c.min_height, "min_height"));
  // K can never exceed the points the GMM is fitted on (the down-sampled candidates).
  cropsight::detail::check_range(where, "gmm.components", c.gmm.components,
                                 Range::at_most(c.sampling.target_points, "sampling.target_points"));
}

Config load_config(const std::string& preset) {
  const auto path = io::find_preset(preset);
  Config cfg;
  apply_config(cfg, io::load_config_map(path), path.string());
  cfg.validate(path.string());
  return cfg;
}

}  // namespace cropsight::pipeline::seedling
