// PointNetConfig's checks and the feature-set names: plain C++, shared by the PointSegmenter
// facade (cropsight_nn) and the libtorch backend plugin (compiled into both).

#include "cropsight/core/error.hpp"
#include "cropsight/nn/point_segmenter.hpp"

namespace cropsight::nn {

int feature_channels(const std::string& f) {
  if (f == "xyz") return 3;
  if (f == "xyzn" || f == "xyzrgb") return 6;
  if (f == "xyzrgbn") return 9;
  throw Error("features", "unknown feature set '" + f + "' (expected xyz, xyzn, xyzrgb or xyzrgbn)");
}

void PointNetConfig::validate(const std::string& where) const {
  if (arch != "pointresnet" && arch != "pointnet2")
    throw Error(where, "'arch' must be pointresnet or pointnet2, got '" + arch + "'");
  try {
    feature_channels(features);
  } catch (const Error&) {
    throw Error(where, "'features' must be xyz, xyzn, xyzrgb or xyzrgbn, got '" + features + "'");
  }
  check_config(*this, where);
  // Fields that visit() does not expose (set by the code that builds the network) still get the
  // same Range rules and wording.
  cropsight::detail::check_range(where, "num_classes", num_classes, Range::at_least(2));
  cropsight::detail::check_range(where, "scale_min", scale_min, Range::above(0));
  cropsight::detail::check_range(where, "scale_max", scale_max, Range::at_least(scale_min, "scale_min"));
  cropsight::detail::check_range(where, "jitter_sigma", jitter_sigma, Range::at_least(0));
  cropsight::detail::check_range(where, "colour_jitter", colour_jitter, Range::at_least(0));
}

}  // namespace cropsight::nn
