#pragma once
// Orthographic pictures of a point cloud: every point drawn as a small square in its colour, the
// points nearest the viewer on top. Used for labelled grape clouds on the demo page.
//
// A view looks along -(right x up): `right` maps to image x (to the right), `up` to image -y (up
// the page). Coordinates are the cloud's own (metres, or the grape dataset's unit-sphere units).
#include <Eigen/Core>
#include <vector>

#include "cropsight/core/cloud.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight::report {

struct CloudView {
  Eigen::Vector3f right = Eigen::Vector3f::UnitX(), up = Eigen::Vector3f::UnitY();  ///< unit, orthogonal
  float left = 0, top = 0;  ///< cloud units: the view's right- and up-coordinates of pixel corner (0, 0)
  float px_per_unit = 100;
  int width = 100, height = 100;  ///< px

  /// Image position (x right, y down, pixel corners; svg_overlay.hpp) of the cloud point `p`.
  Eigen::Vector2f pixel(const Eigen::Vector3f& p) const;
};

/// The view along -(right x up) framing `points` (the part of the cloud worth looking at), `width`
/// pixels wide with a margin of `margin` times the extent on each side; the height follows the
/// extent. Throws Error("cloud view", ...) for no points or width < 16.
CloudView fit_cloud_view(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& right,
                         const Eigen::Vector3f& up, int width, float margin = 0.06f);

/// The points of `cloud` in `colors` (one per point) as seen in `view`, each a square of
/// `point_px` pixels on `background`; nearer points (larger right x up coordinate) drawn last.
/// Throws Error("cloud view", ...) when `colors` and the cloud differ in size.
ColorImage render_cloud(const Cloud& cloud, const std::vector<Rgb8>& colors, const CloudView& view, int point_px,
                        Rgb8 background = {255, 255, 255});

}  // namespace cropsight::report
