#pragma once
// Private helper: a nanoflann k-d tree over a contiguous array of 3-float points (used by the
// statistical outlier filter and by Euclidean clustering). Not a public header: nanoflann stays
// out of include/.
#include <nanoflann.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace cropsight::geometry::detail {

/// Points as x0 y0 z0 x1 y1 z1 ... (float, metres).
struct PackedPoints {
  std::vector<float> xyz;

  std::size_t kdtree_get_point_count() const { return xyz.size() / 3; }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const { return xyz[3 * i + dim]; }
  template <class BBOX>
  bool kdtree_get_bbox(BBOX&) const {
    return false;
  }
};

using PointKdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PackedPoints>, PackedPoints,
                                                        3, std::uint32_t>;

/// Leaf size 10 (nanoflann's default) balances build and query time for ~10^5 points.
inline nanoflann::KDTreeSingleIndexAdaptorParams kdtree_params() {
  return nanoflann::KDTreeSingleIndexAdaptorParams(10);
}

}  // namespace cropsight::geometry::detail
