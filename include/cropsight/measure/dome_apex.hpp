#pragma once
// The apex of a head's dome from the points that are visible of it.
//
// A broccoli head is a dome seen from above. When leaves hide one side of it, the centroid of the
// visible points (or of their top) is pulled towards the visible side, by up to the head's radius;
// the dome's curvature still says where its highest point is. fit_dome_apex fits the paraboloid
//
//   z = k·((x − mx)² + (y − my)²) + b·(x − mx) + c·(y − my) + d      (k > 0: the dome bulges towards
//                                                                      the camera, whose z grows away)
//
// by least squares (mx, my: the points' mean, for conditioning) and returns its apex
// (mx − b/2k, my − c/2k) and the fitted depth there. Camera frame, metres: x right, y down, z
// along the view; the camera looks about straight down, so the dome's axis is about the z axis.
//
// The fit is refused (nullopt) when it does not describe a head: fewer than kMinPoints points, a
// radius of curvature 1/(2k) outside [kMinRadius, kMaxRadius] (flat or saddle-shaped patches,
// leaves), or an apex outside the points' x–y bounding box grown by half its size on each side
// (an extrapolation the visible part does not support). Pure function; thread-safe.
#include <Eigen/Core>
#include <optional>
#include <span>

namespace cropsight::measure {

struct DomeApexLimits {
  static constexpr int kMinPoints = 20;
  static constexpr double kMinRadius = 0.015;  ///< m; florets' bumps are smaller
  static constexpr double kMaxRadius = 0.30;   ///< m; flatter is a leaf or soil
};

/// The apex (camera frame, metres) of the dome through `points`, or nullopt (see above).
std::optional<Eigen::Vector3f> fit_dome_apex(std::span<const Eigen::Vector3f> points);

}  // namespace cropsight::measure
