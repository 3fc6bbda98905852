#pragma once
// The seedling's top view: a raster of the soil plane. The pipeline's densification step and the
// evaluator's IoU both use it, so that a detection and its ground truth are rasterised alike.
#include <Eigen/Core>
#include <vector>

#include "cropsight/core/image.hpp"

namespace cropsight::pipeline::seedling {

/// A raster of the soil plane: cell (i, j) covers plane coordinates origin + (i, j) * cell along
/// the axes e1 = n.unitOrthogonal(), e2 = n x e1.
struct TopViewMask {
  GrayImage mask;  ///< 255 = seedling
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double cell = 0;
  double area() const;  ///< m^2 of set cells
};

/// Rasterises points (any frame, same as the plane) onto the soil plane n . x + d = 0 with the
/// given cell; `origin` is chosen so that both masks of an IoU share one grid (pass the same
/// origin and size). Cells holding a point are set, then closed with a 3x3 kernel.
TopViewMask rasterize_top_view(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& n, double cell,
                               const Eigen::Vector2d& origin, int width, int height);

}  // namespace cropsight::pipeline::seedling
