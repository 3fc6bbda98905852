#pragma once
// Orientation accuracy (paper Table 4.3): the error of an axis angle is the smallest
// difference modulo 180° (an axis has no head or tail), so it lies in [0°, 90°]. Figures are
// degrees; times milliseconds.
#include <string>
#include <vector>

namespace cropsight::eval {

/// Smallest difference of two axis angles, modulo 180°: 179° vs 1° = 2°. Degrees in, degrees out.
double axis_angle_error_deg(double truth_deg, double estimate_deg);

/// One measured potato.
struct OrientationSample {
  std::string file;         ///< the image the estimate came from
  int potato = 0;           ///< which physical potato (data set's numbering)
  std::string light;        ///< light level, e.g. "high", "low"
  double truth_deg = 0;     ///< trigonometric, degrees
  bool ok = false;          ///< false: no box or no mask; counts as a 90° error (the worst)
  double estimate_deg = 0;  ///< trigonometric, degrees, [0, 180)
  double ms = 0;            ///< time of the orientation step for this potato
};

/// MAE and standard deviation of the absolute errors over a group of samples.
struct OrientationStats {
  std::string key;  ///< group name ("all", "high", "45", "potato 1" …)
  int count = 0;
  int failures = 0;    ///< samples with ok = false (counted at 90°)
  double mae_deg = 0;  ///< mean absolute error
  double std_deg = 0;  ///< population standard deviation of the absolute errors
  double max_deg = 0;
};

struct OrientationEvaluation {
  OrientationStats all;
  std::vector<OrientationStats> per_light, per_angle, per_potato;  ///< sorted by key (angles numerically)
  double ms_per_potato = 0;                                        ///< mean of OrientationSample::ms
  std::vector<OrientationSample> samples;
  std::vector<double> errors_deg;  ///< one per sample, same order
};

/// The figures of a set of samples (empty set: zero counts).
OrientationEvaluation summarise_orientation(std::vector<OrientationSample> samples);

}  // namespace cropsight::eval
