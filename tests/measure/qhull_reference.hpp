#pragma once
// The reference hull for the measure tests: qhull through pcl::ConvexHull, the library the
// paper used. Returns input indices.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/surface/convex_hull.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <vector>

namespace cropsight::measure::reference {

struct ReferenceHull {
  std::vector<int> vertices;                  // ascending input indices
  std::vector<std::array<int, 3>> triangles;  // input indices
};

inline ReferenceHull qhull_of(const std::vector<Eigen::Vector3f>& pts) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr in(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : pts) in->points.emplace_back(p.x(), p.y(), p.z());
  in->width = std::uint32_t(in->size());
  in->height = 1;
  pcl::ConvexHull<pcl::PointXYZ> hull;
  hull.setDimension(3);
  hull.setInputCloud(in);
  pcl::PointCloud<pcl::PointXYZ> out;
  std::vector<pcl::Vertices> polys;
  hull.reconstruct(out, polys);
  pcl::PointIndices used;
  hull.getHullPointIndices(used);
  ReferenceHull r;
  r.vertices = used.indices;
  for (const auto& p : polys)
    r.triangles.push_back({used.indices[std::size_t(p.vertices[0])], used.indices[std::size_t(p.vertices[1])],
                           used.indices[std::size_t(p.vertices[2])]});
  std::sort(r.vertices.begin(), r.vertices.end());
  return r;
}

}  // namespace cropsight::measure::reference
