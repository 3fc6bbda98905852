// PointNetConfig's checks and the feature-set names: plain C++, shared by the PointSegmenter
// facade (cropsight_nn) and the libtorch backend plugin (compiled into both).
#include <cmath>
#include <limits>
#include <locale>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/core/threads.hpp"
#include "cropsight/nn/point_segmenter.hpp"

namespace cropsight::nn {

int feature_channels(const std::string& f) {
  if (f == "xyz") return 3;
  if (f == "xyzn" || f == "xyzrgb") return 6;
  if (f == "xyzrgbn") return 9;
  throw Error("features", "unknown feature set '" + f + "' (expected xyz, xyzn, xyzrgb or xyzrgbn)");
}

namespace {
std::string shortest(double v) {
  std::ostringstream o;
  o.imbue(std::locale::classic());
  o << v;
  return o.str();
}

}  // namespace

void PointNetConfig::validate(const std::string& where) const {
  auto fail = [&](const char* key, const std::string& rule, const std::string& got) {
    throw Error(where, std::string("'") + key + "' " + rule + ", got " + got);
  };
  auto at_least = [&](const char* key, int value, int min, const std::string& why = "") {
    if (value < min) fail(key, "must be at least " + std::to_string(min) + why, std::to_string(value));
  };
  // Finite and within [lo, hi] (open at an end when the flag says so).
  auto within = [&](const char* key, double value, double lo, bool lo_open, double hi, bool hi_open) {
    const bool ok =
        std::isfinite(value) && (lo_open ? value > lo : value >= lo) && (hi_open ? value < hi : value <= hi);
    if (ok) return;
    std::string rule = std::isinf(hi) ? std::string(lo_open ? "must be > " : "must be >= ") + shortest(lo)
                                      : std::string("must be in ") + (lo_open ? "(" : "[") + shortest(lo) + ", " +
                                            shortest(hi) + (hi_open ? ")" : "]");
    fail(key, rule, shortest(value));
  };
  const double inf = std::numeric_limits<double>::infinity();
  if (arch != "pointresnet" && arch != "pointnet2") fail("arch", "must be pointresnet or pointnet2", "'" + arch + "'");
  try {
    feature_channels(features);
  } catch (const Error&) {
    fail("features", "must be xyz, xyzn, xyzrgb or xyzrgbn", "'" + features + "'");
  }
  at_least("num_classes", num_classes, 2);
  // The set abstractions need a few points to group (the smallest network that still trains).
  at_least("num_points", num_points, 8);
  at_least("sa1_points", sa1_points, 4);
  at_least("sa2_points", sa2_points, 2);
  at_least("sa3_points", sa3_points, 1);
  at_least("k1", k1, 1);
  at_least("k2", k2, 1);
  at_least("k3", k3, 1);
  at_least("width", width, 1);
  within("dropout", dropout, 0, false, 1, true);
  at_least("epochs", epochs, 1);
  // Steps of a single cloud are skipped (BatchNorm), so batch_size 1 would train nothing.
  at_least("batch_size", batch_size, 2, " (BatchNorm needs two clouds per step)");
  within("lr", lr, 0, true, inf, false);
  within("lr_decay", lr_decay, 0, true, 1, false);
  at_least("lr_step", lr_step, 1);
  within("weight_decay", weight_decay, 0, false, inf, false);
  within("class_weight_power", class_weight_power, 0, false, inf, false);
  within("lovasz_weight", lovasz_weight, 0, false, inf, false);
  within("scale_min", scale_min, 0, true, inf, false);
  within("scale_max", scale_max, scale_min, false, inf, false);
  within("jitter_sigma", jitter_sigma, 0, false, inf, false);
  within("colour_jitter", colour_jitter, 0, false, inf, false);
  at_least("val_every", val_every, 0);
  at_least("threads", threads, 1);
  if (threads > kMaxThreads) fail("threads", "must be at most " + std::to_string(kMaxThreads), std::to_string(threads));
}

}  // namespace cropsight::nn
