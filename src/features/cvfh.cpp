// CVFH through pcl::CVFHEstimation (the real implementation). The segment's usable points are
// copied into small PCL clouds; a fresh estimator per call, because PCL's CVFHEstimation keeps
// its dominant normals between compute() calls.
#include "cropsight/features/cvfh.hpp"

#include <pcl/features/cvfh.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <cmath>

#include "cropsight/core/error.hpp"

namespace cropsight::features {

void compute_cvfh(const OrganizedCloud& cloud, std::span<const int> indices, const CvfhConfig& cfg, float* out) {
  std::fill(out, out + kCvfhBins, 0.0f);
  if (!(cfg.cluster_tolerance > 0.0f) || !(cfg.radius_normals > 0.0f) || cfg.min_points < 1)
    throw Error("cvfh", "cluster_tolerance and radius_normals must be > 0 and min_points >= 1");
  if (!cloud.has_normals()) return;
  auto points = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  auto normals = pcl::make_shared<pcl::PointCloud<pcl::Normal>>();
  points->reserve(indices.size());
  normals->reserve(indices.size());
  for (int i : indices) {
    if (!(std::isfinite(cloud.z[i]) && std::isfinite(cloud.nx[i]))) continue;
    points->push_back(pcl::PointXYZ(cloud.x[i], cloud.y[i], cloud.z[i]));
    const float c = cloud.curvature.empty() ? 0.0f : cloud.curvature[i];
    normals->push_back(pcl::Normal(cloud.nx[i], cloud.ny[i], cloud.nz[i], std::isfinite(c) ? c : 0.0f));
  }
  if (points->size() < 2) return;
  pcl::CVFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::VFHSignature308> cvfh;
  cvfh.setInputCloud(points);
  cvfh.setInputNormals(normals);
  cvfh.setSearchMethod(pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
  cvfh.setViewPoint(0.0f, 0.0f, 0.0f);
  cvfh.setEPSAngleThreshold(cfg.eps_angle);
  cvfh.setCurvatureThreshold(cfg.curvature_threshold);
  cvfh.setClusterTolerance(cfg.cluster_tolerance);
  cvfh.setRadiusNormals(cfg.radius_normals);
  cvfh.setMinPoints(std::size_t(cfg.min_points));
  cvfh.setNormalizeBins(cfg.normalize_bins);
  pcl::PointCloud<pcl::VFHSignature308> result;
  cvfh.compute(result);
  if (result.empty()) return;
  for (const auto& sig : result)
    for (int b = 0; b < kCvfhBins; ++b) out[b] += sig.histogram[b];
  const float inv = 1.0f / float(result.size());
  for (int b = 0; b < kCvfhBins; ++b) out[b] *= inv;
}

}  // namespace cropsight::features
